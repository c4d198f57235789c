// The angle of a vector from its two components, atan2(s, c) for s >= 0, in [0, pi]: the
// contour integral's inner loop (internal header). Within 2 ulp of std::atan2 (tests check
// it) at half its cost: glibc's atan2 is correctly rounded, and saves and restores the
// rounding mode on every call.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

namespace rad::ff {

// atan(s / c) in [0, pi] for s >= 0 (and c of either sign; 0 when both are 0). The ratio of
// the smaller to the larger, t in [0, 1], is moved to the nearest k / 16 by atan's addition
// rule, atan t = atan(k/16) + atan x with x = (t - k/16) / (1 + t k/16), |x| <= 1/32, where
// six terms of atan's series leave under 1e-19.
inline double angle_from_sides(double s, double c) {
    static constexpr std::array<double, 17> kAtanSixteenths = {
        0.0,
        0.06241880999595735,
        0.12435499454676144,
        0.18534794999569476,
        0.24497866312686414,
        0.3028848683749714,
        0.35877067027057225,
        0.4124104415973873,
        0.4636476090008061,
        0.5123894603107377,
        0.5585993153435624,
        0.6022873461349642,
        0.6435011087932844,
        0.6823165548747481,
        0.7188299996216245,
        0.7531512809621944,
        0.7853981633974483,
    };
    const double along = std::abs(c);
    const bool steep = s > along;
    const double t = steep ? along / s : (along > 0 ? s / along : 0);
    const int k = static_cast<int>(t * 16 + 0.5);
    const double nearest = k * (1.0 / 16);
    const double x = (t - nearest) / (1 + t * nearest);
    const double x2 = x * x;
    const double series =
        x + x * x2 * (-1.0 / 3 + x2 * (1.0 / 5 + x2 * (-1.0 / 7 + x2 * (1.0 / 9 - x2 / 11))));
    double angle = kAtanSixteenths[k] + series;
    if (steep) angle = std::numbers::pi / 2 - angle;
    if (c < 0) angle = std::numbers::pi - angle;
    return angle;
}

} // namespace rad::ff
