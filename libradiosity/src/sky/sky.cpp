// The sky's luminance: uniform, the traditional CIE overcast sky and the 15 CIE standard
// general skies (ISO 15469:2004 / CIE S 011); Perez's all-weather sky is in perez_sky.cpp.
#include "radiosity/sky.hpp"
#include "formfactor/sampling.hpp"
#include "radiosity/error.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace rad {
namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

// 1 + a exp(b / cos Z), the gradation (CIE) or its Perez form; 1 at the horizon when b < 0.
double gradation(double a, double b, double cos_zenith) {
    if (cos_zenith <= 1e-9) return b < 0 ? 1 : 1 + a * std::exp(50.0);
    return 1 + a * std::exp(std::min(50.0, b / cos_zenith));
}
} // namespace

std::array<double, 5> Sky::cie_parameters(int type) {
    // ISO 15469: six gradation groups (a, b) and six indicatrix groups (c, d, e).
    static constexpr double kGradation[6][2] = {{4.0, -0.70},  {1.1, -0.8},   {0.0, -1.0},
                                                {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15}};
    static constexpr double kIndicatrix[6][3] = {{0, -1.0, 0},     {2, -1.5, 0.15},
                                                 {5, -2.5, 0.30},  {10, -3.0, 0.45},
                                                 {16, -3.0, 0.30}, {24, -2.8, 0.15}};
    static constexpr int kGroups[15][2] = {{0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 0},
                                           {2, 1}, {2, 2}, {2, 3}, {3, 1}, {3, 2},
                                           {3, 3}, {4, 3}, {4, 4}, {5, 4}, {5, 5}};
    if (type < 1 || type > 15)
        throw InputError("CIE standard sky type " + std::to_string(type) +
                         " does not exist: the types are 1 (overcast, steep gradation) to 15 "
                         "(cloudless, turbid, broad corona)");
    const auto& g = kGradation[kGroups[type - 1][0]];
    const auto& i = kIndicatrix[kGroups[type - 1][1]];
    return {g[0], g[1], i[0], i[1], i[2]};
}

double Sky::sun_zenith_rad() const {
    return sun_.zenith * kDeg;
}

double Sky::relative(double zenith, double to_sun) const {
    return relative_cos(std::cos(zenith), std::cos(to_sun));
}

double Sky::relative_cos(double cos_zenith, double cos_to_sun) const {
    const auto& [a, b, c, d, e] = p_;
    switch (model_) {
    case Model::uniform:
        return 1;
    case Model::cie_overcast:
        return (1 + 2 * cos_zenith) / 3;
    case Model::cie_standard: {
        const double chi = std::acos(std::clamp(cos_to_sun, -1.0, 1.0));
        const double indicatrix =
            1 + c * (std::exp(d * chi) - std::exp(d * kPi / 2)) + e * cos_to_sun * cos_to_sun;
        return gradation(a, b, cos_zenith) * indicatrix / cie_zenith_;
    }
    case Model::perez: {
        const double gamma = std::acos(std::clamp(cos_to_sun, -1.0, 1.0));
        return std::max(
            0.0, gradation(a, b, cos_zenith) *
                     (1 + c * std::exp(std::min(50.0, d * gamma)) + e * cos_to_sun * cos_to_sun));
    }
    }
    return 0;
}

double Sky::luminance_at(double altitude_deg, double azimuth_deg) const {
    return luminance(frame_.direction(altitude_deg, azimuth_deg));
}

double Sky::luminance(const Vec3& d) const {
    if (d[1] < 0) return ground_;
    return scale_ * relative_cos(d[1], dot(d, sun_direction_));
}

// Scales the sky so that its horizontal illuminance is `lux`: the integral of relative x
// cos over the hemisphere, Gauss-Legendre in sin(altitude) by 0.75-degree steps of azimuth
// from the sun's (a sun's corona a few degrees wide is resolved). The integrand is
// symmetric about the sun's vertical plane: half the circle, twice.
double Sky::relative_integral() const {
    static const auto table = [] {
        struct Table {
            std::vector<double> nodes, weights, cos_step;
        } t;
        ff::gauss_legendre(48, t.nodes, t.weights);
        constexpr int kSteps = 240; // over [0, pi]
        for (int j = 0; j < kSteps; ++j) t.cos_step.push_back(std::cos((j + 0.5) * kPi / kSteps));
        return t;
    }();
    const double sun_sin = std::cos(sun_zenith_rad()), sun_cos = std::sin(sun_zenith_rad());
    double integral = 0;
    for (std::size_t k = 0; k < table.nodes.size(); ++k) {
        const double u = table.nodes[k]; // sin(altitude), nodes on [0, 1]
        const double c = std::sqrt(std::max(0.0, 1 - u * u));
        double ring = 0;
        for (const double cos_step : table.cos_step)
            ring += relative_cos(u, u * sun_sin + c * sun_cos * cos_step);
        integral += table.weights[k] * u * ring * (2 * kPi / double(table.cos_step.size()));
    }
    return integral;
}

void Sky::normalise_to(double lux) {
    normalise_to(lux, relative_integral());
}

void Sky::normalise_to(double lux, double integral) {
    if (!(integral > 0)) throw InputError("the sky's luminance integrates to nothing");
    scale_ = lux > 0 ? lux / integral : 0;
    horizontal_ = lux;
}

void Sky::set_ground(double reflectance) {
    if (!(reflectance >= 0 && reflectance <= 1))
        throw InputError("the ground's reflectance must be between 0 and 1");
    const double sun_horizontal = sun_up() ? sun_normal_lux_ * std::cos(sun_zenith_rad()) : 0.0;
    ground_ = reflectance * (horizontal_ + sun_horizontal) / kPi;
}

std::string Sky::describe() const {
    char text[160];
    std::snprintf(text, sizeof text, "%s: %.6g lux on the horizontal, zenith %.6g cd/m^2",
                  name_.c_str(), horizontal_, zenith_luminance());
    std::string out = text;
    if (model_ == Model::cie_standard || model_ == Model::perez) {
        std::snprintf(text, sizeof text, ", sun at altitude %.2f azimuth %.2f deg", sun_.altitude(),
                      sun_.azimuth);
        out += text;
    }
    if (sun_normal_lux_ > 0) {
        std::snprintf(text, sizeof text, ", sun beam %.6g lux", sun_normal_lux_);
        out += text;
    }
    return out;
}

Sky Sky::uniform(double luminance, const SkyFrame& frame, double ground_reflectance) {
    if (!(luminance >= 0 && std::isfinite(luminance)))
        throw InputError("a uniform sky's luminance must be a number >= 0");
    Sky s;
    s.model_ = Model::uniform;
    s.frame_ = frame;
    s.name_ = "uniform sky";
    s.scale_ = luminance;
    s.horizontal_ = kPi * luminance;
    s.set_ground(ground_reflectance);
    return s;
}

Sky Sky::cie_overcast(double lux, const SkyFrame& frame, double ground_reflectance) {
    if (!(lux >= 0 && std::isfinite(lux)))
        throw InputError("a sky's horizontal illuminance must be a number >= 0");
    Sky s;
    s.model_ = Model::cie_overcast;
    s.frame_ = frame;
    s.name_ = "CIE overcast sky";
    s.scale_ = lux * 9 / (7 * kPi); // Lz: the horizontal illuminance is 7 pi Lz / 9
    s.horizontal_ = lux;
    s.set_ground(ground_reflectance);
    return s;
}

Sky::DayAvailability Sky::availability(Day day) {
    switch (day) {
    case Day::partly_cloudy:
        return {7, {300, 45000, 1}, 0.80, "partly cloudy sky (CIE 7, IES daylight availability)"};
    case Day::overcast:
        return {1, {300, 21000, 1}, 0, "overcast sky (CIE 1, IES daylight availability)"};
    case Day::clear:
        break;
    }
    return {12, {800, 15500, 0.5}, 0.21, "clear sky (CIE 12, IES daylight availability)"};
}

Sky Sky::of_day(Day day, const SunPosition& sun, const SkyFrame& frame, double ground_reflectance) {
    const auto a = availability(day);
    const double altitude = sun.altitude() * kDeg;
    if (altitude <= 0) {
        auto dark = cie_standard(a.cie_type, sun, 0, frame, ground_reflectance);
        dark.name_ =
            std::string(a.name).substr(0, std::string(a.name).find(" (")) + " (the sun is down)";
        return dark;
    }
    const double s = std::sin(altitude);
    const double diffuse =
        a.diffuse[0] +
        a.diffuse[1] * (a.diffuse[2] == 0.5 ? std::sqrt(s) : std::pow(s, a.diffuse[2]));
    auto sky = cie_standard(a.cie_type, sun, diffuse, frame, 0);
    sky.sun_normal_lux_ = a.extinction > 0 ? 127500 * std::exp(-a.extinction / s) : 0.0;
    sky.name_ = a.name;
    sky.set_ground(ground_reflectance);
    return sky;
}

Sky Sky::clear(const SunPosition& sun, const SkyFrame& frame, double ground_reflectance) {
    return of_day(Day::clear, sun, frame, ground_reflectance);
}

Sky Sky::cie_standard(int type, const SunPosition& sun, double lux, const SkyFrame& frame,
                      double ground_reflectance) {
    if (!(lux >= 0 && std::isfinite(lux)))
        throw InputError("a sky's horizontal illuminance must be a number >= 0");
    Sky s;
    s.model_ = Model::cie_standard;
    s.frame_ = frame;
    s.p_ = cie_parameters(type);
    s.sun_ = sun;
    {
        // The denominator of L / Lz: the gradation at the zenith x the indicatrix at the sun.
        const auto& [a, b, c, d, e] = s.p_;
        const double zs = std::min(sun.zenith, 90.0) * kDeg;
        s.cie_zenith_ = gradation(a, b, 1) * (1 + c * (std::exp(d * zs) - std::exp(d * kPi / 2)) +
                                              e * std::cos(zs) * std::cos(zs));
    }
    // The CIE skies are defined for the sun on or above the horizon.
    s.sun_.zenith = std::min(sun.zenith, 90.0);
    s.sun_direction_ = frame.direction(s.sun_.altitude(), sun.azimuth);
    s.name_ = "CIE standard sky type " + std::to_string(type);
    s.normalise_to(lux);
    s.set_ground(ground_reflectance);
    return s;
}

} // namespace rad
