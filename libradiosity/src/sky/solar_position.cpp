// NREL's Solar Position Algorithm (Reda and Andreas, "Solar position algorithm for solar
// radiation applications", NREL/TP-560-34302, 2008), written from the report's steps.
#include "radiosity/sky.hpp"
#include "sky/spa_tables.hpp"

#include <cmath>
#include <numbers>

namespace rad {
namespace {
constexpr double kDeg = std::numbers::pi / 180;

double wrap360(double degrees) {
    const double d = std::fmod(degrees, 360.0);
    return d < 0 ? d + 360 : d;
}

// Julian day at 0h UT of a Gregorian calendar date.
double julian_day(int year, int month, int day) {
    if (month < 3) year -= 1, month += 12;
    const double a = std::floor(year / 100.0);
    const double b = 2 - a + std::floor(a / 4);
    return std::floor(365.25 * (year + 4716)) + std::floor(30.6001 * (month + 1)) + day + b -
           1524.5;
}

// Sum over series k of (sum_i a cos(b + c x)) x^k, / 1e8: one heliocentric coordinate.
double heliocentric(std::span<const std::span<const sky::PeriodicTerm>> series, double jme) {
    double total = 0, power = 1;
    for (const auto& terms : series) {
        double sum = 0;
        for (const auto& t : terms) sum += t.a * std::cos(t.b + t.c * jme);
        total += sum * power;
        power *= jme;
    }
    return total / 1e8;
}

// Nutation in longitude and obliquity (degrees) at Julian ephemeris century `jce`.
void nutation(double jce, double& delta_psi, double& delta_epsilon) {
    const double t = jce, t2 = t * t, t3 = t2 * t;
    const std::array<double, 5> x{297.85036 + 445267.111480 * t - 0.0019142 * t2 + t3 / 189474,
                                  357.52772 + 35999.050340 * t - 0.0001603 * t2 - t3 / 300000,
                                  134.96298 + 477198.867398 * t + 0.0086972 * t2 + t3 / 56250,
                                  93.27191 + 483202.017538 * t - 0.0036825 * t2 + t3 / 327270,
                                  125.04452 - 1934.136261 * t + 0.0020708 * t2 + t3 / 450000};
    double psi = 0, eps = 0;
    for (const auto& term : sky::nutation_terms()) {
        double arg = 0;
        for (int k = 0; k < 5; ++k) arg += term.y[std::size_t(k)] * x[std::size_t(k)];
        psi += (term.a + term.b * t) * std::sin(arg * kDeg);
        eps += (term.c + term.d * t) * std::cos(arg * kDeg);
    }
    delta_psi = psi / 36000000;
    delta_epsilon = eps / 36000000;
}

// The true obliquity of the ecliptic (degrees).
double obliquity(double jme, double delta_epsilon) {
    const double u = jme / 10;
    double poly = 0, power = 1;
    for (double c :
         {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45}) {
        poly += c * power;
        power *= u;
    }
    return poly / 3600 + delta_epsilon;
}

struct Geocentric {
    double ascension, declination, sidereal, radius; // degrees, degrees, degrees, AU
};

Geocentric geocentric_sun(double jd, double delta_t) {
    const double jde = jd + delta_t / 86400;
    const double jc = (jd - 2451545) / 36525, jce = (jde - 2451545) / 36525, jme = jce / 10;
    const double l = wrap360(heliocentric(sky::longitude_terms(), jme) / kDeg);
    const double b = heliocentric(sky::latitude_terms(), jme) / kDeg;
    const double r = heliocentric(sky::radius_terms(), jme);
    const double theta = wrap360(l + 180), beta = -b;
    double delta_psi = 0, delta_epsilon = 0;
    nutation(jce, delta_psi, delta_epsilon);
    const double epsilon = obliquity(jme, delta_epsilon);
    const double lambda = theta + delta_psi - 20.4898 / (3600 * r);
    const double nu0 = wrap360(280.46061837 + 360.98564736629 * (jd - 2451545) +
                               0.000387933 * jc * jc - jc * jc * jc / 38710000);
    const double nu = nu0 + delta_psi * std::cos(epsilon * kDeg);
    const double sl = std::sin(lambda * kDeg), ce = std::cos(epsilon * kDeg),
                 se = std::sin(epsilon * kDeg);
    const double alpha =
        wrap360(std::atan2(sl * ce - std::tan(beta * kDeg) * se, std::cos(lambda * kDeg)) / kDeg);
    const double delta =
        std::asin(std::sin(beta * kDeg) * ce + std::cos(beta * kDeg) * se * sl) / kDeg;
    return {alpha, delta, nu, r};
}
} // namespace

SunPosition solar_position(const Location& where, const LocalTime& when, double delta_t) {
    const double jd =
        julian_day(when.year, when.month, when.day) + (when.hour - where.time_zone) / 24;
    const auto g = geocentric_sun(jd, delta_t);
    const double h = wrap360(g.sidereal + where.longitude - g.ascension); // local hour angle
    // Topocentric: the observer's parallax.
    const double phi = where.latitude * kDeg;
    const double xi = 8.794 / (3600 * g.radius) * kDeg;
    const double u = std::atan(0.99664719 * std::tan(phi));
    const double x = std::cos(u) + where.elevation / 6378140 * std::cos(phi);
    const double y = 0.99664719 * std::sin(u) + where.elevation / 6378140 * std::sin(phi);
    const double delta = g.declination * kDeg, hr = h * kDeg;
    const double denominator = std::cos(delta) - x * std::sin(xi) * std::cos(hr);
    const double delta_alpha = std::atan2(-x * std::sin(xi) * std::sin(hr), denominator);
    const double delta_topo =
        std::atan2((std::sin(delta) - y * std::sin(xi)) * std::cos(delta_alpha), denominator);
    const double h_topo = hr - delta_alpha;
    // Elevation, refracted above the horizon.
    const double e0 = std::asin(std::sin(phi) * std::sin(delta_topo) +
                                std::cos(phi) * std::cos(delta_topo) * std::cos(h_topo)) /
                      kDeg;
    double refraction = 0;
    constexpr double kSunRadius = 0.26667, kRefractionAtHorizon = 0.5667;
    if (e0 >= -(kSunRadius + kRefractionAtHorizon))
        refraction = where.pressure / 1010 * 283 / (273 + where.temperature) * 1.02 /
                     (60 * std::tan((e0 + 10.3 / (e0 + 5.11)) * kDeg));
    const double gamma = std::atan2(std::sin(h_topo), std::cos(h_topo) * std::sin(phi) -
                                                          std::tan(delta_topo) * std::cos(phi)) /
                         kDeg;
    SunPosition out;
    out.zenith = 90 - (e0 + refraction);
    out.azimuth = wrap360(gamma + 180);
    out.earth_sun_distance = g.radius;
    return out;
}

} // namespace rad
