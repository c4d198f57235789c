// gs: Gauss-Seidel, the paper's solver: each sweep uses the values updated earlier in it.
#include "sweep.hpp"

namespace rad::solve_impl {
namespace {
class GaussSeidel final : public Solver {
  public:
    std::string_view name() const override { return "gs"; }
    std::string_view summary() const override { return "Gauss-Seidel (the paper's)"; }
    bool shooting() const override { return false; }
    long default_max_iterations(std::size_t) const override { return 100000; }
    SolveResult solve(const TransportOperator& op, const Channels& emission,
                      const SolveControl& control) const override {
        return solve_by_sweeps(op, emission, control, true);
    }
};
} // namespace

const Solver& gs_solver() {
    static const GaussSeidel solver;
    return solver;
}
} // namespace rad::solve_impl
