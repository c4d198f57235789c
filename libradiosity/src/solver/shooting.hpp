// What the shooting solvers (PR, APR) share: progressive refinement, optionally displayed
// with Cohen et al.'s ambient term (internal header).
#pragma once
#include "radiosity/solver.hpp"

namespace rad::solve_impl {

SolveResult shoot(const TransportOperator& op, const Channels& emission,
                  const SolveControl& control, bool ambient);

// A shooting solver: progressive refinement, with or without the ambient display term;
// one iteration is one shot.
class ShootingSolver final : public Solver {
  public:
    ShootingSolver(std::string_view name, std::string_view summary, bool ambient)
        : name_(name), summary_(summary), ambient_(ambient) {}
    std::string_view name() const override { return name_; }
    std::string_view summary() const override { return summary_; }
    bool shooting() const override { return true; }
    long default_max_iterations(std::size_t patches) const override {
        return 1000 * static_cast<long>(patches);
    }
    SolveResult solve(const TransportOperator& op, const Channels& emission,
                      const SolveControl& control) const override {
        return shoot(op, emission, control, ambient_);
    }

  private:
    std::string_view name_, summary_;
    bool ambient_;
};

} // namespace rad::solve_impl
