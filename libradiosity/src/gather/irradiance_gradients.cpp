// Ward and Heckbert's irradiance gradients over a stratified hemisphere (see the header).
#include "radiosity/irradiance_gradients.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rad {

namespace {
Vec3 in_plane(const Vec3& tu, const Vec3& tv, double phi) {
    return tu * std::cos(phi) + tv * std::sin(phi);
}

// Adds s x (a - b) to grad's channels along `axis`.
void add_difference(std::array<Vec3, 3>& grad, const Vec3& axis, double s, const Rgb& a,
                    const Rgb& b) {
    for (int c = 0; c < 3; ++c) grad[c] = grad[c] + axis * (s * (a[c] - b[c]));
}

// The nearer of two cells' distances; 0 when either met nothing.
double nearer(const HemisphereCell& a, const HemisphereCell& b) {
    return a.distance > 0 && b.distance > 0 ? std::min(a.distance, b.distance) : 0;
}
} // namespace

HemisphereGridSize hemisphere_grid(int rays) {
    const double wanted = std::max(rays, 1);
    HemisphereGridSize size;
    size.m = std::max(1, int(std::lround(std::sqrt(wanted / std::numbers::pi))));
    size.n = std::max(1, int(std::lround(wanted / size.m)));
    return size;
}

Vec3 hemisphere_cell_direction(int j, int k, int m, int n, double u, double v, const Vec3& normal,
                               const Vec3& tu, const Vec3& tv) {
    return cosine_direction(normal, tu, tv, (j + u) / m, (k + v) / n);
}

IrradianceGradients irradiance_gradients(std::span<const HemisphereCell> cells, int m, int n,
                                         const Vec3& tu, const Vec3& tv) {
    constexpr double pi = std::numbers::pi;
    IrradianceGradients out;
    // Per sector: its middle's direction u_k, the turn's axis there (u_k a quarter turn back),
    // and the direction its first border moves along (v_k-, a quarter turn on from it).
    thread_local std::vector<Vec3> middle, turn, border;
    middle.resize(std::size_t(n));
    turn.resize(std::size_t(n));
    border.resize(std::size_t(n));
    for (int k = 0; k < n; ++k) {
        const double mid = 2 * pi * (k + 0.5) / n, start = 2 * pi * k / n;
        middle[k] = in_plane(tu, tv, mid);
        turn[k] = tu * std::sin(mid) - tv * std::cos(mid);
        border[k] = tu * -std::sin(start) + tv * std::cos(start);
    }
    for (int j = 0; j < m; ++j) {
        // The ring's lower border (theta_j-), its middle and its upper border (theta_j+).
        const double cos_low = std::sqrt(1 - double(j) / m), sin_low = std::sqrt(double(j) / m);
        const double cos_mid = std::sqrt(1 - (j + 0.5) / m), sin_mid = std::sqrt((j + 0.5) / m);
        const double cos_high = std::sqrt(std::max(0.0, 1 - double(j + 1) / m));
        for (int k = 0; k < n; ++k) {
            const auto& cell = cells[std::size_t(j) * n + k];
            for (int c = 0; c < 3; ++c) out.mean[c] += cell.radiance[c];
            // Turning the normal towards the cell weighs it by cos: d(cos)/d(turn) = tan.
            add_difference(out.rotational, turn[k], -sin_mid / cos_mid, cell.radiance,
                           Rgb{0, 0, 0});
            if (j > 0) { // the border with the ring below moves along u_k
                const auto& below = cells[std::size_t(j - 1) * n + k];
                if (const double r = nearer(cell, below); r > 0)
                    add_difference(out.translational, middle[k],
                                   2 * pi * cos_low * cos_low * sin_low / (n * r), cell.radiance,
                                   below.radiance);
            }
            // The border with the previous sector moves along v_k-.
            const auto& before = cells[std::size_t(j) * n + (k + n - 1) % n];
            if (const double r = nearer(cell, before); r > 0)
                add_difference(out.translational, border[k],
                               cos_mid * (cos_low - cos_high) / (sin_mid * r), cell.radiance,
                               before.radiance);
        }
    }
    // Ward and Heckbert's sums are of irradiance (pi / (m n) x the radiance's sum): here all
    // is over pi, as the mean is.
    const double count = double(m) * n;
    for (int c = 0; c < 3; ++c) {
        out.mean[c] /= count;
        out.rotational[c] = out.rotational[c] * (1 / count);
        out.translational[c] = out.translational[c] * (1 / pi);
    }
    return out;
}

} // namespace rad
