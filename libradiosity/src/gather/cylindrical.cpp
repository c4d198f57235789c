// Cylindrical illuminance: the luminaires exactly, the room by eight vertical gathers.
#include "radiosity/cylindrical.hpp"

#include "radiosity/rays.hpp"
#include "radiosity/sensors.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace rad {
namespace {

// Two horizontal unit vectors (perpendicular to `up` and to each other).
void horizontal_frame(const Vec3& up, Vec3& a, Vec3& b) {
    const Vec3 helper = std::abs(up[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    a = normalized(cross(up, helper));
    b = cross(up, a);
}

Vec3 azimuth(const Vec3& a, const Vec3& b, int k, int count) {
    const double phi = 2 * std::numbers::pi * k / count;
    return a * std::cos(phi) + b * std::sin(phi);
}

// One luminaire's Ez (lux).
double luminaire_cylindrical(const Gatherer& gatherer, const LuminaireSet& set, const Luminaire& l,
                             const Vec3& point, const Vec3& up) {
    const LuminaireOptics optics{&gatherer.specular(), nullptr};
    const Vec3 to = l.position - point;
    const Vec3 across = to - up * dot(to, up);
    const double opening = set.opening_size(l);
    if (opening <= 0 || length(to) >= 5 * opening) {
        // A point source: on the vertical plane facing it, I sin(theta) / d^2; Ez is that
        // over pi. Straight above or below, neither.
        if (!(length(across) > 1e-9 * length(to))) return 0;
        return luminaire_illuminance(set, l, point, normalized(across), &gatherer.scene(), optics) /
               std::numbers::pi;
    }
    Vec3 a, b;
    horizontal_frame(up, a, b);
    constexpr int kNear = 32;
    double sum = 0;
    for (int k = 0; k < kNear; ++k)
        sum += luminaire_illuminance(set, l, point, azimuth(a, b, k, kNear), &gatherer.scene(),
                                     optics);
    return sum / kNear;
}

} // namespace

CylindricalIlluminance cylindrical_illuminance(const Gatherer& gatherer,
                                               const LuminaireSet* luminaires, const Box& box,
                                               const Vec3& point, const Vec3& up,
                                               std::uint64_t index, std::string& problem) {
    CylindricalIlluminance out;
    problem = out_of_reach(point, box);
    if (!problem.empty()) return out;
    double exact = 0;
    if (luminaires)
        for (const auto& l : luminaires->luminaires)
            exact += luminaire_cylindrical(gatherer, *luminaires, l, point, up);
    // The solution's light, direction by direction; the luminaires' share counts in each
    // direction's relative accuracy target.
    const Rgb known{exact / kRadianceEfficacy, exact / kRadianceEfficacy,
                    exact / kRadianceEfficacy};
    Vec3 a, b;
    horizontal_frame(up, a, b);
    double room = 0, variance = 0;
    for (int k = 0; k < kCylinderAzimuths; ++k) {
        const auto r = gatherer.gather(point, azimuth(a, b, k, kCylinderAzimuths),
                                       index * (kCylinderAzimuths + 1) + std::uint64_t(k), known);
        if (r.sees_backs(gatherer.options().max_back_fraction)) {
            problem = "most of what the point sees are backs of surfaces: it is inside an "
                      "object or behind a surface (move it)";
            return out;
        }
        room += lux(r.total());
        const double e = kRadianceEfficacy * r.luminous_error;
        variance += std::isfinite(e) ? e * e : 0;
        out.at_budget = out.at_budget || r.at_budget;
    }
    out.cylindrical = exact + room / kCylinderAzimuths;
    out.error = std::sqrt(variance) / kCylinderAzimuths;
    const auto h = gather_sensor(gatherer, luminaires, box, point, up,
                                 index * (kCylinderAzimuths + 1) + kCylinderAzimuths, problem);
    // Eh has no value where facing up the point sees backs; Ez stands.
    out.horizontal = problem.empty() ? lux(h.total()) : std::numeric_limits<double>::quiet_NaN();
    problem.clear();
    return out;
}

} // namespace rad
