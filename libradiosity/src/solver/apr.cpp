// apr: progressive refinement displayed with the ambient term, which lights every patch at
// once and decays to zero as the solution converges.
#include "shooting.hpp"

namespace rad::solve_impl {
namespace {
class ProgressiveAmbient final : public Solver {
  public:
    std::string_view name() const override { return "apr"; }
    std::string_view summary() const override { return "pr plus Cohen's ambient term for display"; }
    bool shooting() const override { return true; }
    long default_max_iterations(std::size_t patches) const override {
        return 1000 * static_cast<long>(patches);
    }
    SolveResult solve(const TransportOperator& op, const Channels& emission,
                      const SolveControl& control) const override {
        return shoot(op, emission, control, true);
    }
};
} // namespace

const Solver& apr_solver() {
    static const ProgressiveAmbient solver;
    return solver;
}
} // namespace rad::solve_impl
