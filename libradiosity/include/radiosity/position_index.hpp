// The position index of glare: how much less a source troubles the eye the farther it lies
// from the line of sight, for the glare formulas that divide by it (UGR, DGP).
#pragma once
#include "radiosity/vec.hpp"

namespace rad {

// Guth's position index (the IES Lighting Handbook's fit, as Radiance's evalglare uses it):
// `tau_deg`, the angle from the vertical of the plane holding the line of sight and the
// source; `sigma_deg`, the angle between the line of sight and the source. Not capped: a
// luminaire outside the table's extent is left out (inside_position_table), as CIE 117 does.
double guth_position_index(double tau_deg, double sigma_deg);

// Evalglare's position index: Guth's (the IES Lighting Handbook's fit) above the line of
// sight, Iwata's (CIE 2010) below it, at most 16.
double dgp_position_index(const Vec3& view, const Vec3& up, const Vec3& source,
                          double* sigma_deg = nullptr, double* tau_deg = nullptr);

} // namespace rad
