// A small basis for relighting a daylight solution by sky (the viewer page): principal
// components of the solutions under a year of skies, weighted by the patches' areas.
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/gather.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rad {
namespace {

using Matrix = std::vector<std::vector<double>>; // square, symmetric

// Cyclic Jacobi: the eigenvalues of symmetric `a` (destroyed) and their eigenvectors as the
// columns of the returned matrix, largest eigenvalue first.
Matrix eigen_symmetric(Matrix a, std::vector<double>& values) {
    const std::size_t n = a.size();
    Matrix v(n, std::vector<double>(n, 0.0));
    for (std::size_t i = 0; i < n; ++i) v[i][i] = 1;
    for (int sweep = 0; sweep < 60; ++sweep) {
        double off = 0, diagonal = 0;
        for (std::size_t p = 0; p < n; ++p) {
            diagonal += a[p][p] * a[p][p];
            for (std::size_t q = p + 1; q < n; ++q) off += a[p][q] * a[p][q];
        }
        if (off <= 1e-22 * diagonal || off == 0) break;
        for (std::size_t p = 0; p < n; ++p)
            for (std::size_t q = p + 1; q < n; ++q) {
                if (std::abs(a[p][q]) <= 1e-300) continue;
                const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
                const double t =
                    (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
                const double c = 1 / std::sqrt(t * t + 1), s = t * c;
                for (std::size_t k = 0; k < n; ++k) { // columns p, q
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (std::size_t k = 0; k < n; ++k) { // rows p, q
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (std::size_t k = 0; k < n; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto x, auto y) { return a[x][x] > a[y][y]; });
    values.clear();
    Matrix sorted(n, std::vector<double>(n, 0.0));
    for (std::size_t k = 0; k < n; ++k) {
        values.push_back(a[order[k]][order[k]]);
        for (std::size_t i = 0; i < n; ++i) sorted[i][k] = v[i][order[k]];
    }
    return sorted;
}

// G[s][t] = sum over patches j and channels c of area_j r[j,s,c] r[j,t,c].
Matrix area_gram(const DaylightSolution& solution, const std::vector<double>& areas) {
    const std::size_t count = solution.patches.count();
    Matrix g(count, std::vector<double>(count, 0.0));
    const auto& r = solution.radiosity;
    for (std::size_t j = 0; j < areas.size(); ++j) {
        const float* row = &r[j * count * 3];
        for (std::size_t s = 0; s < count; ++s) {
            const double a0 = areas[j] * row[3 * s], a1 = areas[j] * row[3 * s + 1],
                         a2 = areas[j] * row[3 * s + 2];
            if (a0 == 0 && a1 == 0 && a2 == 0) continue;
            for (std::size_t t = s; t < count; ++t)
                g[s][t] += a0 * row[3 * t] + a1 * row[3 * t + 1] + a2 * row[3 * t + 2];
        }
    }
    for (std::size_t s = 0; s < count; ++s)
        for (std::size_t t = 0; t < s; ++t) g[s][t] = g[t][s];
    return g;
}

} // namespace

namespace {
// The principal directions of the solutions under `skies`, as sky-patch weights z_k (the
// component u_k = A z_k, area-orthonormal), largest first, at most `max_components`; and
// the area Gram matrix G = A^T W A they were found with.
struct Directions {
    std::vector<std::vector<double>> z;
    Matrix g;
};
Directions principal_directions(const DaylightSolution& solution, const std::vector<double>& areas,
                                const std::vector<std::vector<double>>& skies, int max_components) {
    const std::size_t count = solution.patches.count();
    // Y = A L over the skies; its principal directions u = A z / sqrt(lambda), from the
    // symmetric H = R^T G R with C = L L^T = R R^T (R = E D^1/2) and G = A^T W A.
    Matrix c(count, std::vector<double>(count, 0.0));
    for (const auto& sky : skies)
        for (std::size_t s = 0; s < count; ++s)
            for (std::size_t t = 0; t < count; ++t)
                c[s][t] += sky[s] / kRadianceEfficacy * sky[t] / kRadianceEfficacy;
    std::vector<double> d;
    const auto e = eigen_symmetric(c, d);
    Matrix r(count, std::vector<double>(count, 0.0));
    for (std::size_t s = 0; s < count; ++s)
        for (std::size_t k = 0; k < count; ++k) r[s][k] = e[s][k] * std::sqrt(std::max(0.0, d[k]));
    Directions out{{}, area_gram(solution, areas)};
    const auto& g = out.g;
    Matrix h(count, std::vector<double>(count, 0.0));
    {
        Matrix gr(count, std::vector<double>(count, 0.0)); // G R
        for (std::size_t s = 0; s < count; ++s)
            for (std::size_t t = 0; t < count; ++t)
                if (g[s][t] != 0)
                    for (std::size_t k = 0; k < count; ++k) gr[s][k] += g[s][t] * r[t][k];
        for (std::size_t k = 0; k < count; ++k)
            for (std::size_t l = k; l < count; ++l) {
                double sum = 0;
                for (std::size_t s = 0; s < count; ++s) sum += r[s][k] * gr[s][l];
                h[k][l] = h[l][k] = sum;
            }
    }
    std::vector<double> lambda;
    const auto q = eigen_symmetric(h, lambda);
    // Every usable component's sky-patch weights z = R q_k / sqrt(lambda_k).
    for (std::size_t k = 0; k < count && int(k) < max_components; ++k) {
        if (!(lambda[k] > 1e-12 * lambda[0])) break;
        std::vector<double> z(count, 0.0);
        const double norm = 1 / std::sqrt(lambda[k]);
        for (std::size_t s = 0; s < count; ++s)
            for (std::size_t l = 0; l < count; ++l) z[s] += r[s][l] * q[l][k] * norm;
        out.z.push_back(std::move(z));
    }
    return out;
}

// Per number K of components (0 to all), the mean and the worst relative error over the
// skies. The components are orthonormal (area-weighted): a sky's error with the first K is
// sqrt(|y|^2 - sum of its first K weights squared) / |y|, |y|^2 = l^T G l.
void errors_by_count(const Matrix& g, const std::vector<std::vector<double>>& weights,
                     const std::vector<std::vector<double>>& skies, std::vector<double>& mean,
                     std::vector<double>& worst) {
    const std::size_t count = g.size();
    mean.assign(weights.size() + 1, 0.0);
    worst.assign(weights.size() + 1, 0.0);
    for (const auto& sky : skies) {
        double norm2 = 0;
        for (std::size_t s = 0; s < count; ++s)
            for (std::size_t t = 0; t < count; ++t) norm2 += sky[s] * g[s][t] * sky[t];
        norm2 /= kRadianceEfficacy * kRadianceEfficacy;
        if (!(norm2 > 0)) continue;
        double left = norm2;
        for (std::size_t k = 0; k <= weights.size(); ++k) {
            const double error = std::sqrt(std::max(0.0, left) / norm2);
            mean[k] += error / double(skies.size());
            worst[k] = std::max(worst[k], error);
            if (k == weights.size()) break;
            double weight = 0;
            for (std::size_t s = 0; s < count; ++s) weight += weights[k][s] * sky[s];
            left -= weight * weight;
        }
    }
}
} // namespace

DaylightBasis daylight_basis(const DaylightSolution& solution, const std::vector<double>& areas,
                             const std::vector<std::vector<double>>& skies, int max_components,
                             double target_error) {
    if (skies.empty()) throw std::logic_error("a daylight basis needs skies");
    const auto directions = principal_directions(solution, areas, skies, max_components);
    const std::size_t count = solution.patches.count();
    // The weight of a sky: u_k^T W A L = z^T G L (radiance; L in cd/m^2 / 179).
    std::vector<std::vector<double>> weights;
    for (const auto& z : directions.z) {
        std::vector<double> w(count, 0.0);
        for (std::size_t t = 0; t < count; ++t) {
            for (std::size_t s = 0; s < count; ++s) w[t] += z[s] * directions.g[s][t];
            w[t] /= kRadianceEfficacy;
        }
        weights.push_back(std::move(w));
    }
    // The fewest components whose mean error over the skies is at most target_error.
    std::vector<double> mean, worst;
    errors_by_count(directions.g, weights, skies, mean, worst);
    std::size_t used = weights.size();
    for (std::size_t k = 1; k <= weights.size(); ++k)
        if (mean[k] <= target_error) {
            used = k;
            break;
        }
    DaylightBasis basis;
    for (std::size_t k = 0; k < used; ++k) {
        basis.values.push_back(mix_sky_groups(solution, directions.z[k]));
        basis.weights.push_back(weights[k]);
    }
    basis.mean_error = mean[used];
    basis.worst_error = worst[used];
    return basis;
}

YearOfSkies day_year(const SkyPatches& patches, const SkyFrame& frame, const Location& where,
                     double ground, Sky::Day kind) {
    YearOfSkies out;
    static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    std::vector<bool> sun_in(patches.count(), false);
    const auto cells = patches.cells(frame, 4); // once for the year
    for (int day = 1; day <= 365; day += 5) {
        int month = 0, rest = day;
        while (rest > kDays[month]) rest -= kDays[month++];
        for (int hour = 0; hour < 24; ++hour) {
            const auto sun = solar_position(where, {2025, month + 1, rest, hour + 0.5});
            if (sun.zenith >= 90) continue;
            const auto sky = Sky::of_day(kind, sun, frame, ground);
            out.skies.push_back(patches.mean_luminance(sky, cells));
            if (const auto sun_in_patch = sun_patch(patches, sky))
                sun_in[sun_in_patch->patch] = true;
        }
    }
    for (std::size_t p = 0; p < sun_in.size(); ++p)
        if (sun_in[p]) out.sun_patches.push_back(p);
    return out;
}

} // namespace rad
