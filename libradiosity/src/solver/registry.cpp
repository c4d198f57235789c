// The solvers, by name. Adding a solver: one file under src/solver/ that defines
// `const Solver& NAME_solver()`, plus one X(NAME) line here.
#include "core/named_registry.hpp"
#include "radiosity/solver.hpp"

// clang-format off
#define RAD_SOLVERS(X) \
    X(gs)              \
    X(jacobi)          \
    X(pr)              \
    X(apr)             \
    /* one X(name) line per solver, above this line */
// clang-format on

namespace rad {
namespace solve_impl {
#define RAD_DECLARE_SOLVER(name) const Solver& name##_solver();
RAD_SOLVERS(RAD_DECLARE_SOLVER)
#undef RAD_DECLARE_SOLVER
} // namespace solve_impl

std::span<const Solver* const> solvers() {
#define RAD_LIST_SOLVER(name) &solve_impl::name##_solver(),
    static const Solver* const all[] = {RAD_SOLVERS(RAD_LIST_SOLVER)};
#undef RAD_LIST_SOLVER
    return all;
}

std::vector<std::string> solver_names() {
    return names_of(solvers());
}

const Solver& solver(std::string_view name) {
    return find_named(solvers(), name, "solver");
}

} // namespace rad
