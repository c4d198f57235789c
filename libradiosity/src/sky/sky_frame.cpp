// The scene's compass (SkyFrame) and the quantities of the atmosphere the skies share.
#include "radiosity/sky.hpp"

#include <cmath>
#include <numbers>

namespace rad {
namespace {
constexpr double kDeg = std::numbers::pi / 180;
}

Vec3 SkyFrame::north() const {
    return {std::sin(north_deg * kDeg), 0, -std::cos(north_deg * kDeg)};
}
Vec3 SkyFrame::east() const {
    return {std::cos(north_deg * kDeg), 0, std::sin(north_deg * kDeg)};
}
Vec3 SkyFrame::direction(double altitude_deg, double azimuth_deg) const {
    const double c = std::cos(altitude_deg * kDeg);
    return north() * (c * std::cos(azimuth_deg * kDeg)) +
           east() * (c * std::sin(azimuth_deg * kDeg)) + Vec3{0, std::sin(altitude_deg * kDeg), 0};
}
void SkyFrame::angles(const Vec3& d, double& altitude_deg, double& azimuth_deg) const {
    altitude_deg = std::asin(std::clamp(d[1], -1.0, 1.0)) / kDeg;
    double az = std::atan2(dot(d, east()), dot(d, north())) / kDeg;
    azimuth_deg = az < 0 ? az + 360 : az;
}

double eccentricity(int day_of_year) {
    const double g = 2 * std::numbers::pi * (day_of_year - 1) / 365;
    return 1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2 * g) +
           0.000077 * std::sin(2 * g);
}

double air_mass(double zenith_deg) {
    const double z = std::min(zenith_deg, 90.0);
    return 1 / (std::cos(z * kDeg) + 0.50572 * std::pow(96.07995 - z, -1.6364));
}

} // namespace rad
