// pr: progressive refinement: shoot the patch with the most unshot power.
#include "shooting.hpp"

namespace rad::solve_impl {

const Solver& pr_solver() {
    static const ShootingSolver solver("pr", "progressive refinement (one iteration = one shot)",
                                       false);
    return solver;
}

} // namespace rad::solve_impl
