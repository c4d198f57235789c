// gs: Gauss-Seidel, the paper's solver: each sweep uses the values updated earlier in it.
#include "sweep.hpp"

namespace rad::solve_impl {

const Solver& gs_solver() {
    static const SweepSolver solver("gs", "Gauss-Seidel (the paper's)", true);
    return solver;
}

} // namespace rad::solve_impl
