// Perez's all-weather sky (Perez, Seals and Michalsky 1993, Solar Energy 50(3)) from direct
// normal and diffuse horizontal irradiance, with Perez et al.'s 1990 luminous efficacies
// (Solar Energy 44(5)) for the illuminances. Coefficients as published (the tables Radiance's
// gendaymtx also uses).
#include "radiosity/error.hpp"
#include "radiosity/sky.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace rad {
namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kSolarConstant = 1367; // W/m^2
constexpr int kClearestBin = 7;
// Perez's sky brightness, clamped to where his fits hold.
constexpr double kLeastBrightness = 0.01, kMostBrightness = 0.6;

// Table 1 of the 1993 paper: per clearness bin, a..e each as (x1, x2, x3, x4).
constexpr double kPerez[8][20] = {
    {1.3525, -0.2576, -0.2690, -1.4366, -0.7670, 0.0007, 1.2734, -0.1233, 2.8000,  0.6004,
     1.2375, 1.0000,  1.8734,  0.6297,  0.9738,  0.2809, 0.0356, -0.1246, -0.5718, 0.9938},
    {-1.2219, -0.7730, 1.4148,  1.1016,  -0.2054, 0.0367, -3.9128, 0.9156, 6.9750,  0.1774,
     6.4477,  -0.1239, -1.5798, -0.5081, -1.7812, 0.1080, 0.2624,  0.0672, -0.2190, -0.4285},
    {-1.1000,  -0.2515, 0.8952,  0.0156, 0.2782, -0.1812, -4.5000, 1.1766, 24.7219, -13.0812,
     -37.7000, 34.8438, -5.0000, 1.5218, 3.9229, -2.6204, -0.0156, 0.1597, 0.4199,  -0.5562},
    {-0.5484,  -0.6654, -0.2672, 0.7117, 0.7234, -0.6219, -5.6812, 2.6297,  33.3389, -18.3000,
     -62.2500, 52.0781, -3.5000, 0.0016, 1.1477, 0.1062,  0.4659,  -0.3296, -0.0876, -0.0329},
    {-0.6000,  -0.3566, -2.5000, 2.3250,  0.2937, 0.0496, -5.6812, 1.8415, 21.0000, -4.7656,
     -21.5906, 7.2492,  -3.5000, -0.1554, 1.4062, 0.3988, 0.0032,  0.0766, -0.0656, -0.1294},
    {-1.0156, -0.3670, 1.0078,  1.4051,  0.2875,  -0.5328, -3.8500, 3.3750, 14.0000, -0.9999,
     -7.1406, 7.5469,  -3.4000, -0.1078, -1.0750, 1.5702,  -0.0672, 0.4016, 0.3017,  -0.4844},
    {-1.0000, 0.0211,  0.5025,  -0.5119, -0.3000, 0.1922, 0.7023, -1.6317, 19.0000, -5.0000,
     1.2438,  -1.9094, -4.0000, 0.0250,  0.3844,  0.2656, 1.0468, -0.3788, -2.4517, 1.4656},
    {-1.0500,  0.0289,  0.4260,  0.3590, -0.3250, 0.1156, 0.7781, 0.0025,  31.0625, -14.5000,
     -46.1148, 55.3750, -7.2312, 0.4050, 13.3500, 0.6234, 1.5000, -0.6426, 1.8564,  0.5636}};
constexpr double kClearnessBounds[9] = {1.000, 1.065, 1.230, 1.500, 1.950,
                                        2.800, 4.500, 6.200, 12.01};
// Table 4 of the 1990 paper: diffuse (eqn. 7) and direct (eqn. 8) efficacy, a b c d.
constexpr double kDiffuseEfficacy[8][4] = {
    {97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90}, {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98}};
constexpr double kDirectEfficacy[8][4] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};

int clearness_bin(double epsilon) {
    for (int k = 0; k < 8; ++k)
        if (epsilon < kClearnessBounds[k + 1]) return k;
    return 7;
}

// The five parameters of the luminance distribution (eqns. 6-8), sun zenith in radians.
std::array<double, 5> perez_parameters(int bin, double zenith, double brightness, double epsilon) {
    if (epsilon > 1.065 && epsilon < 2.8 && brightness < 0.2) brightness = 0.2;
    const auto x = [&](int i, int j) { return kPerez[bin][4 * i + j]; };
    const auto linear = [&](int i) {
        return x(i, 0) + x(i, 1) * zenith + brightness * (x(i, 2) + x(i, 3) * zenith);
    };
    std::array<double, 5> p{linear(0), linear(1), linear(2), linear(3), linear(4)};
    if (bin == 0) {
        p[2] = std::exp(std::pow(brightness * (x(2, 0) + x(2, 1) * zenith), x(2, 2))) - x(2, 3);
        p[3] =
            -std::exp(brightness * (x(3, 0) + x(3, 1) * zenith)) + x(3, 2) + brightness * x(3, 3);
    }
    return p;
}
} // namespace

Sky Sky::perez(double direct_normal, double diffuse_horizontal, const SunPosition& sun,
               int day_of_year, double dew_point, const SkyFrame& frame,
               double ground_reflectance) {
    if (!(direct_normal >= 0 && diffuse_horizontal >= 0 && std::isfinite(direct_normal) &&
          std::isfinite(diffuse_horizontal)))
        throw InputError("a Perez sky needs direct normal and diffuse horizontal irradiance "
                         ">= 0 (W/m^2)");
    Sky s;
    s.model_ = Model::perez;
    s.frame_ = frame;
    s.sun_ = sun;
    s.sun_.zenith = std::min(sun.zenith, 90.0);
    s.sun_direction_ = frame.direction(s.sun_.altitude(), sun.azimuth);
    s.name_ = "Perez sky";
    const double beam = sun.zenith < 90 ? direct_normal : 0.0;
    const double z = s.sun_.zenith * kPi / 180;
    const double water = std::exp(0.07 * dew_point - 0.075); // precipitable, cm
    if (diffuse_horizontal <= 0) { // night, or no data: a dark sky, the sun alone
        s.p_ = {0, -1, 0, -1, 0};
        s.scale_ = s.horizontal_ = 0;
        // No diffuse light is the clearest sky there is: the beam keeps that bin's efficacy.
        const auto& be = kDirectEfficacy[kClearestBin];
        s.sun_normal_lux_ =
            beam * std::max(0.0, be[0] + be[1] * water + be[2] * std::exp(5.73 * z - 5) +
                                     be[3] * kLeastBrightness);
    } else {
        const double z3 = 1.041 * z * z * z;
        const double epsilon = std::clamp(
            ((diffuse_horizontal + beam) / diffuse_horizontal + z3) / (1 + z3), 1.0, 12.0);
        const double brightness = std::clamp(diffuse_horizontal * air_mass(s.sun_.zenith) /
                                                 (kSolarConstant * eccentricity(day_of_year)),
                                             kLeastBrightness, kMostBrightness);
        const int bin = clearness_bin(epsilon);
        const auto& de = kDiffuseEfficacy[bin];
        const double diffuse_lux =
            diffuse_horizontal *
            (de[0] + de[1] * water + de[2] * std::cos(z) + de[3] * std::log(brightness));
        const auto& be = kDirectEfficacy[bin];
        s.sun_normal_lux_ =
            beam * std::max(0.0, be[0] + be[1] * water + be[2] * std::exp(5.73 * z - 5) +
                                     be[3] * brightness);
        s.p_ = perez_parameters(bin, z, brightness, epsilon);
        // Low brightness at some clearness makes the distribution negative over the whole
        // sky: its parameters are taken at the least brightness that gives a sky.
        double raised = brightness;
        double integral = s.relative_integral();
        while (!(integral > 0) && raised < kMostBrightness) {
            raised = std::min(kMostBrightness, raised * 1.25 + 0.005);
            s.p_ = perez_parameters(bin, z, raised, epsilon);
            integral = s.relative_integral();
        }
        if (!(integral > 0)) { // never met: the overcast distribution
            s.p_ = {0, -1, 0, -1, 0};
            s.model_ = Model::cie_overcast;
            s.adjusted_ = "Perez's distribution is negative over the whole sky at every "
                          "brightness for its clearness: the CIE overcast distribution";
            integral = s.relative_integral();
        } else if (raised != brightness) {
            char text[200];
            std::snprintf(text, sizeof text,
                          "Perez's distribution is negative over the whole sky at its brightness "
                          "%.3g: taken at %.3g",
                          brightness, raised);
            s.adjusted_ = text;
        }
        s.normalise_to(std::max(0.0, diffuse_lux), integral);
    }
    s.set_ground(ground_reflectance);
    return s;
}

} // namespace rad
