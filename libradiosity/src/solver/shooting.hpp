// What the shooting solvers (PR, APR) share: progressive refinement, optionally displayed
// with Cohen et al.'s ambient term (internal header).
#pragma once
#include "radiosity/solver.hpp"

namespace rad::solve_impl {

SolveResult shoot(const TransportOperator& op, const Channels& emission,
                  const SolveControl& control, bool ambient);

} // namespace rad::solve_impl
