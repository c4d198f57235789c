// apr: progressive refinement displayed with the ambient term, which lights every patch at
// once and decays to zero as the solution converges.
#include "shooting.hpp"

namespace rad::solve_impl {

const Solver& apr_solver() {
    static const ShootingSolver solver("apr", "pr plus Cohen's ambient term for display", true);
    return solver;
}

} // namespace rad::solve_impl
