// Cylindrical illuminance: the luminaires exactly, the room by eight vertical gathers.
#include "radiosity/cylindrical.hpp"

#include "radiosity/rays.hpp"
#include "radiosity/sensors.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

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

// Ez and E_sc from the vertical illuminance at `count` azimuths k 2 pi / count: Ez is their
// mean; E_sc facing `facing_angle` adds (2 / pi^2) x the integral of Ev(phi) cos(phi - facing),
// (4 / (pi count)) x the sum (exact for the light's first harmonic). Their weights per sample.
double cylinder_weight(int count) {
    return 1.0 / count;
}
double semi_weight(int k, int count, double facing_angle) {
    const double phi = 2 * std::numbers::pi * k / count;
    return 1.0 / count + 4 / (std::numbers::pi * count) * std::cos(phi - facing_angle);
}

// One luminaire's Ez and E_sc (lux): a far one exactly, I sin(theta) / (pi d^2) (its
// illuminance on the vertical plane facing it over pi) times 1 + cos of the horizontal angle
// between the facing and the luminaire for E_sc; a near one by 32 azimuths.
std::pair<double, double> luminaire_cylindrical(const Gatherer& gatherer, const LuminaireSet& set,
                                                const Luminaire& l, const Vec3& point,
                                                const Vec3& up, const Vec3& a, const Vec3& b,
                                                double facing_angle) {
    const LuminaireOptics optics{&gatherer.specular(), nullptr};
    const Vec3 to = l.position - point;
    const Vec3 across = to - up * dot(to, up);
    const double opening = set.opening_size(l);
    if (opening <= 0 || length(to) >= 5 * opening) {
        if (!(length(across) > 1e-9 * length(to))) return {0, 0}; // straight above or below
        const Vec3 toward = normalized(across);
        const double ez = luminaire_illuminance(set, l, point, toward, &gatherer.scene(), optics) /
                          std::numbers::pi;
        const double psi = std::atan2(dot(toward, b), dot(toward, a)) - facing_angle;
        return {ez, ez * (1 + std::cos(psi))};
    }
    constexpr int kNear = 32;
    double ez = 0, esc = 0;
    for (int k = 0; k < kNear; ++k) {
        const double ev = luminaire_illuminance(set, l, point, azimuth(a, b, k, kNear),
                                                &gatherer.scene(), optics);
        ez += cylinder_weight(kNear) * ev;
        esc += semi_weight(k, kNear, facing_angle) * ev;
    }
    return {ez, esc};
}

} // namespace

CylindricalIlluminance cylindrical_illuminance(const Gatherer& gatherer,
                                               const LuminaireSet* luminaires, const Box& box,
                                               const Vec3& point, const Vec3& up,
                                               std::uint64_t index, std::string& problem,
                                               const Vec3* facing) {
    CylindricalIlluminance out;
    problem = out_of_reach(point, box);
    if (!problem.empty()) return out;
    Vec3 a, b;
    horizontal_frame(up, a, b);
    const double facing_angle = facing ? std::atan2(dot(*facing, b), dot(*facing, a)) : 0.0;
    double exact_z = 0, exact_sc = 0;
    if (luminaires)
        for (const auto& l : luminaires->luminaires) {
            const auto [ez, esc] =
                luminaire_cylindrical(gatherer, *luminaires, l, point, up, a, b, facing_angle);
            exact_z += ez, exact_sc += esc;
        }
    // The solution's light, direction by direction; the luminaires' share counts in each
    // direction's relative accuracy target.
    const double known_lux = facing ? exact_sc : exact_z;
    const Rgb known{known_lux / kRadianceEfficacy, known_lux / kRadianceEfficacy,
                    known_lux / kRadianceEfficacy};
    double room_z = 0, room_sc = 0, variance_z = 0, variance_sc = 0;
    for (int k = 0; k < kCylinderAzimuths; ++k) {
        const auto r = gatherer.gather(point, azimuth(a, b, k, kCylinderAzimuths),
                                       index * (kCylinderAzimuths + 1) + std::uint64_t(k), known);
        if (r.sees_backs(gatherer.options().max_back_fraction)) {
            problem = "most of what the point sees are backs of surfaces: it is inside an "
                      "object or behind a surface (move it)";
            return out;
        }
        const double wz = cylinder_weight(kCylinderAzimuths);
        const double wsc = semi_weight(k, kCylinderAzimuths, facing_angle);
        const double e = kRadianceEfficacy * r.luminous_error;
        const double e2 = std::isfinite(e) ? e * e : 0;
        room_z += wz * lux(r.total());
        room_sc += wsc * lux(r.total());
        variance_z += wz * wz * e2;
        variance_sc += wsc * wsc * e2;
        out.at_budget = out.at_budget || r.at_budget;
    }
    out.cylindrical = exact_z + room_z;
    out.error = std::sqrt(variance_z);
    if (facing) {
        out.semi_cylindrical = exact_sc + room_sc;
        out.semi_error = std::sqrt(variance_sc);
    }
    const auto h = gather_sensor(gatherer, luminaires, box, point, up,
                                 index * (kCylinderAzimuths + 1) + kCylinderAzimuths, problem);
    // Eh has no value where facing up the point sees backs; Ez stands.
    out.horizontal = problem.empty() ? lux(h.total()) : std::numeric_limits<double>::quiet_NaN();
    problem.clear();
    return out;
}

} // namespace rad
