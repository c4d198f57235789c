// The position index of glare (position_index.hpp): Guth's, and evalglare's with Iwata's below
// the line of sight.
#include "radiosity/position_index.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {
namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = 180 / kPi;
constexpr double kMaxPositionIndex = 16; // evalglare's cap
} // namespace

double guth_position_index(double tau_deg, double sigma_deg) {
    const double t = tau_deg, s = sigma_deg;
    const double p = std::exp((35.2 - 0.31889 * t - 1.22 * std::exp(-2 * t / 9)) * 1e-3 * s +
                              (21 + 0.26667 * t - 0.002963 * t * t) * 1e-5 * s * s);
    return p;
}

double dgp_position_index(const Vec3& view, const Vec3& up, const Vec3& source, double* sigma_deg,
                          double* tau_deg) {
    const double cos_sigma = std::clamp(dot(view, source), -1.0, 1.0);
    const double sigma = std::acos(cos_sigma) * kDeg;
    // tau: around the line of sight, from the vertical (evalglare's pict_get_tau).
    const Vec3 across = source * (1 / std::max(cos_sigma, 1e-9)) - view;
    const double tau = length(across) > 0
                           ? std::acos(std::clamp(dot(up, normalized(across)), -1.0, 1.0)) * kDeg
                           : 0.0;
    if (sigma_deg) *sigma_deg = sigma;
    if (tau_deg) *tau_deg = tau;
    // Above or below the line of sight (evalglare's pict_get_vangle).
    const Vec3 below = cross(view, cross(view, up));
    const double elevation = std::acos(std::clamp(dot(below, source), -1.0, 1.0)) - 0.5 * kPi;
    double p = guth_position_index(tau, sigma);
    if (elevation < 0) {
        const double c = std::cos(tau / kDeg);
        const double beta =
            std::atan(std::tan(sigma / kDeg) * std::sqrt(1 + 0.3225 * c * c)) * kDeg;
        p = std::exp(6.49e-3 * beta + 21e-5 * beta * beta);
    }
    return std::min(p, kMaxPositionIndex);
}

} // namespace rad
