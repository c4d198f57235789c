// Reinhart's sky subdivision (and Tregenza's, its MF:1), as Radiance's reinhart.cal and
// gendaymtx lay it out.
#include "radiosity/sky_patches.hpp"
#include "radiosity/error.hpp"

#include <cmath>
#include <numbers>

namespace rad {
namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;
constexpr int kTregenzaRows = 7;
constexpr int kTregenzaPerRow[kTregenzaRows] = {30, 30, 24, 24, 18, 12, 6};
} // namespace

SkyPatches SkyPatches::parse(const std::string& spec) {
    if (spec == "tregenza") return SkyPatches(1);
    const std::string prefix = "reinhart:";
    if (spec.rfind(prefix, 0) == 0) {
        const auto digits = spec.substr(prefix.size());
        if (!digits.empty() && digits.size() <= 2 &&
            digits.find_first_not_of("0123456789") == std::string::npos) {
            const int m = std::stoi(digits);
            if (m >= 1 && m <= 12) return SkyPatches(m);
        }
    }
    throw InputError("sky subdivision '" + spec +
                     "' is not known: give reinhart:M for M = 1..12 (1: Tregenza's 145 patches, "
                     "2: 577, 4: 2305), or tregenza");
}

SkyPatches::SkyPatches(int subdivisions) : m_(subdivisions) {
    alpha_ = 90.0 / (kTregenzaRows * m_ + 0.5);
    std::size_t next = 0;
    for (int row = 0; row < kTregenzaRows * m_; ++row) {
        first_.push_back(next);
        per_row_.push_back(kTregenzaPerRow[row / m_] * m_);
        next += std::size_t(per_row_.back());
    }
    first_.push_back(next); // the zenith cap
}

std::size_t SkyPatches::patch_of(double altitude, double azimuth) const {
    if (altitude < 0) return 0;
    const int row = int(altitude / alpha_);
    if (row >= int(per_row_.size())) return first_.back() + 1;
    const int n = per_row_[std::size_t(row)];
    double a = std::fmod(azimuth, 360.0);
    if (a < 0) a += 360;
    const int j = int(std::floor(a * n / 360.0 + 0.5)) % n;
    return first_[std::size_t(row)] + std::size_t(j) + 1;
}

std::size_t SkyPatches::patch_of(const SkyFrame& frame, const Vec3& direction) const {
    double altitude = 0, azimuth = 0;
    frame.angles(direction, altitude, azimuth);
    return patch_of(altitude, azimuth);
}

std::string SkyPatches::name(std::size_t patch) const {
    return patch == 0 ? "ground" : "sky" + std::to_string(patch);
}

SkyPatches::Bounds SkyPatches::bounds(std::size_t patch) const {
    if (patch == 0) return {-90, 0, 0, 360};
    if (patch == first_.back() + 1) return {90 - alpha_ / 2, 90, 0, 360};
    std::size_t row = 0;
    while (row + 1 < per_row_.size() && first_[row + 1] < patch) ++row;
    const double width = 360.0 / per_row_[row];
    const double centre = double(patch - 1 - first_[row]) * width;
    return {row * alpha_, (row + 1) * alpha_, centre - width / 2, centre + width / 2};
}

double SkyPatches::solid_angle(std::size_t patch) const {
    const auto b = bounds(patch);
    return (std::sin(b.altitude1 * kDeg) - std::sin(b.altitude0 * kDeg)) *
           (b.azimuth1 - b.azimuth0) * kDeg;
}

std::vector<Vec3> SkyPatches::cell_directions(const SkyFrame& frame, std::size_t patch,
                                              int side) const {
    const auto b = bounds(patch);
    const double s0 = std::sin(b.altitude0 * kDeg), s1 = std::sin(b.altitude1 * kDeg);
    std::vector<Vec3> out;
    out.reserve(std::size_t(side * side));
    for (int a = 0; a < side; ++a) {
        const double altitude = std::asin(s0 + (s1 - s0) * (a + 0.5) / side) / kDeg;
        for (int z = 0; z < side; ++z)
            out.push_back(frame.direction(altitude, b.azimuth0 + (b.azimuth1 - b.azimuth0) *
                                                                     (z + 0.5) / side));
    }
    return out;
}

Vec3 SkyPatches::cell_direction(const SkyFrame& frame, std::size_t patch, int side, int cell,
                                double u, double v) const {
    const auto b = bounds(patch);
    const double s0 = std::sin(b.altitude0 * kDeg), s1 = std::sin(b.altitude1 * kDeg);
    const int a = cell / side, z = cell % side;
    const double altitude = std::asin(s0 + (s1 - s0) * (a + u) / side) / kDeg;
    return frame.direction(altitude, b.azimuth0 + (b.azimuth1 - b.azimuth0) * (z + v) / side);
}

SkyPatches::Cells SkyPatches::cells(const SkyFrame& frame, int side) const {
    Cells out(count());
    for (std::size_t p = 0; p < count(); ++p) out[p] = cell_directions(frame, p, side);
    return out;
}

std::vector<double> SkyPatches::mean_luminance(const Sky& sky, int side) const {
    return mean_luminance(sky, cells(sky.frame(), side));
}

std::vector<double> SkyPatches::mean_luminance(const Sky& sky, const Cells& cells) const {
    std::vector<double> out(count(), 0.0);
    out[0] = sky.ground_luminance();
    if (sky.horizontal_illuminance() <= 0) return out;
    for (std::size_t p = 1; p < count(); ++p) {
        double sum = 0;
        for (const auto& d : cells[p]) sum += sky.luminance(d);
        out[p] = sum / double(cells[p].size());
    }
    return out;
}

} // namespace rad
