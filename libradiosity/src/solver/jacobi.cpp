// jacobi: each sweep uses only the previous sweep's values (converges more slowly than
// Gauss-Seidel, but every row is independent).
#include "sweep.hpp"

namespace rad::solve_impl {
namespace {
class Jacobi final : public Solver {
  public:
    std::string_view name() const override { return "jacobi"; }
    std::string_view summary() const override { return "Jacobi iteration"; }
    bool shooting() const override { return false; }
    long default_max_iterations(std::size_t) const override { return 100000; }
    SolveResult solve(const TransportOperator& op, const Channels& emission,
                      const SolveControl& control) const override {
        return solve_by_sweeps(op, emission, control, false);
    }
};
} // namespace

const Solver& jacobi_solver() {
    static const Jacobi solver;
    return solver;
}
} // namespace rad::solve_impl
