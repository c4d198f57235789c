// The periodic terms of NREL's Solar Position Algorithm (Reda and Andreas, 2008, tables A4.2
// and A4.3): the Earth's heliocentric longitude, latitude and radius (VSOP87 as Meeus
// abridged it) and the nutation series. Published data, one row a term.
#pragma once
#include <array>
#include <span>

namespace rad::sky {

struct PeriodicTerm {
    double a, b, c; // a cos(b + c x)
};
struct NutationTerm {
    std::array<int, 5> y; // multipliers of X0..X4
    double a, b, c, d;    // (a + b T) sin(arg), (c + d T) cos(arg), 0.0001 arc seconds
};

// L0..L5, B0..B1, R0..R4: each series' rows.
std::span<const std::span<const PeriodicTerm>> longitude_terms();
std::span<const std::span<const PeriodicTerm>> latitude_terms();
std::span<const std::span<const PeriodicTerm>> radius_terms();
std::span<const NutationTerm> nutation_terms();

} // namespace rad::sky
