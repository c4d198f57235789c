// The solvers, by name. Adding a solver: one file under src/solver/ that defines
// `const Solver& NAME_solver()`, plus one X(NAME) line here.
#include "radiosity/error.hpp"
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
    std::vector<std::string> names;
    for (const auto* s : solvers()) names.emplace_back(s->name());
    return names;
}

const Solver& solver(std::string_view name) {
    std::string known;
    for (const auto* s : solvers()) {
        if (s->name() == name) return *s;
        known += (known.empty() ? "" : ", ") + std::string(s->name());
    }
    throw InputError("unknown solver '" + std::string(name) + "' (use " + known + ")");
}

} // namespace rad
