// pr: progressive refinement: shoot the patch with the most unshot power.
#include "shooting.hpp"

namespace rad::solve_impl {
namespace {
class Progressive final : public Solver {
  public:
    std::string_view name() const override { return "pr"; }
    std::string_view summary() const override {
        return "progressive refinement (one iteration = one shot)";
    }
    bool shooting() const override { return true; }
    long default_max_iterations(std::size_t patches) const override {
        return 1000 * static_cast<long>(patches);
    }
    SolveResult solve(const TransportOperator& op, const Channels& emission,
                      const SolveControl& control) const override {
        return shoot(op, emission, control, false);
    }
};
} // namespace

const Solver& pr_solver() {
    static const Progressive solver;
    return solver;
}
} // namespace rad::solve_impl
