// jacobi: each sweep uses only the previous sweep's values (converges more slowly than
// Gauss-Seidel, but every row is independent).
#include "sweep.hpp"

namespace rad::solve_impl {

const Solver& jacobi_solver() {
    static const SweepSolver solver("jacobi", "Jacobi iteration", false);
    return solver;
}

} // namespace rad::solve_impl
