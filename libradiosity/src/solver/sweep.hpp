// What the sweep solvers (Gauss-Seidel, Jacobi) share: one sweep over all rows of F for all
// channels at once, and the loop around it (internal header).
#pragma once
#include "radiosity/solver.hpp"

namespace rad::solve_impl {

// One sweep; `in_place` (Gauss-Seidel) reads the values updated earlier in the same sweep,
// otherwise (Jacobi) only the previous sweep's, kept in `scratch`. Returns sum |B_new - B_old|
// and sum |B_new| over patches and channels.
std::pair<double, double> sweep(const TransportOperator& op, const Channels& emission, Channels& b,
                                Channels& scratch, bool in_place);

// The same over a link hierarchy (op.hierarchy): gather over links with push-pull.
std::pair<double, double> link_sweep(const TransportOperator& op, const Channels& emission,
                                     Channels& b, bool in_place);

// Sweeps until the control's limits, starting from B = E.
SolveResult solve_by_sweeps(const TransportOperator& op, const Channels& emission,
                            const SolveControl& control, bool in_place);

// A sweep solver: Gauss-Seidel (in place) or Jacobi; they differ in that alone.
class SweepSolver final : public Solver {
  public:
    SweepSolver(std::string_view name, std::string_view summary, bool in_place)
        : name_(name), summary_(summary), in_place_(in_place) {}
    std::string_view name() const override { return name_; }
    std::string_view summary() const override { return summary_; }
    bool shooting() const override { return false; }
    long default_max_iterations(std::size_t) const override { return 100000; }
    SolveResult solve(const TransportOperator& op, const Channels& emission,
                      const SolveControl& control) const override {
        return solve_by_sweeps(op, emission, control, in_place_);
    }

  private:
    std::string_view name_, summary_;
    bool in_place_;
};

} // namespace rad::solve_impl
