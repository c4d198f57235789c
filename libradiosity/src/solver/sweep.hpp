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

// Sweeps until the control's limits, starting from B = E.
SolveResult solve_by_sweeps(const TransportOperator& op, const Channels& emission,
                            const SolveControl& control, bool in_place);

} // namespace rad::solve_impl
