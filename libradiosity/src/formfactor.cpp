#include "radiosity/formfactor.hpp"

#include "radiosity/cli.hpp"
#include "radiosity/rays.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>

namespace rad {

namespace {

constexpr double kPi = std::numbers::pi;

// splitmix64: tiny, fast and good enough for sample placement; seeded per row.
struct Rng {
    std::uint64_t state;
    Rng(std::uint64_t seed, std::uint64_t stream)
        : state(seed * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull)) {
        next();
    }
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }
};

// Gauss-Legendre nodes and weights on [0,1].
void gauss_legendre(int m, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(m, 0);
    weights.assign(m, 0);
    for (int i = 0; i < m; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (m + 0.5));
        double dp = 1;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= m; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = m * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-15) break;
        }
        nodes[i] = 0.5 * (1 - x);
        weights[i] = 1.0 / ((1 - x * x) * dp * dp);
    }
}

struct Sample {
    Vec3 point;
    double weight; // fraction of the patch's area this sample stands for; weights sum to 1
};

struct PatchGeometry {
    std::array<Vec3, 4> corners;
    int count;
};

PatchGeometry patch_geometry(const radfmt::MeshData& mesh, const radfmt::Patch& p) {
    PatchGeometry g{};
    g.count = p.corner_count();
    for (int k = 0; k < g.count; ++k) g.corners[k] = mesh.vertices[p.corners[k]];
    return g;
}

// A point of the patch for (s,t) in [0,1]^2 and the area the unit square maps to there:
// bilinear for quads, the collapsed (Duffy) square for triangles.
Vec3 patch_point(const PatchGeometry& g, double s, double t, double& jacobian) {
    const auto& c = g.corners;
    if (g.count == 4) {
        const Vec3 p = c[0] * ((1 - s) * (1 - t)) + c[1] * (s * (1 - t)) + c[2] * (s * t) +
                       c[3] * ((1 - s) * t);
        const Vec3 ds = (c[1] - c[0]) * (1 - t) + (c[2] - c[3]) * t;
        const Vec3 dt = (c[3] - c[0]) * (1 - s) + (c[2] - c[1]) * s;
        jacobian = length(cross(ds, dt));
        return p;
    }
    const Vec3 p = c[0] + (c[1] - c[0]) * s + (c[2] - c[1]) * (s * t);
    jacobian = length(cross(c[1] - c[0], c[2] - c[1])) * s;
    return p;
}

// Quadrature points (Gauss-Legendre product rule) for smooth integrands.
std::vector<Sample> gauss_samples(const PatchGeometry& g, double area,
                                  const std::vector<double>& nodes,
                                  const std::vector<double>& weights) {
    std::vector<Sample> out;
    for (std::size_t a = 0; a < nodes.size(); ++a)
        for (std::size_t b = 0; b < nodes.size(); ++b) {
            double jacobian = 0;
            const Vec3 p = patch_point(g, nodes[a], nodes[b], jacobian);
            out.push_back({p, weights[a] * weights[b] * jacobian / area});
        }
    return out;
}

// The fan triangle (of a convex polygon) that u in [0,1) falls in by area; `remainder`, when
// asked for, is u rescaled to [0,1) within that triangle, so one number can serve twice.
std::size_t pick_fan_triangle(std::span<const double> fan_cdf, double u,
                              double* remainder = nullptr) {
    std::size_t tri = 0;
    double lo = 0;
    while (tri + 1 < fan_cdf.size() && u > fan_cdf[tri]) lo = fan_cdf[tri++];
    if (remainder) *remainder = (u - lo) / std::max(1e-300, fan_cdf[tri] - lo);
    return tri;
}

// An area-uniform point of fan triangle `tri` (vertices 0, tri+1, tri+2) for u, v in [0,1).
Vec3 fan_triangle_point(std::span<const Vec3> poly, std::size_t tri, double u, double v) {
    const double r = std::sqrt(u);
    return poly[0] * (1 - r) + poly[tri + 1] * (r * (1 - v)) + poly[tri + 2] * (r * v);
}

// An area-uniform point on a convex polygon (fan of triangles).
Vec3 uniform_point(std::span<const Vec3> poly, std::span<const double> fan_cdf, double u0,
                   double u1, double u2) {
    return fan_triangle_point(poly, pick_fan_triangle(fan_cdf, u0), u1, u2);
}

std::vector<double> fan_cdf(std::span<const Vec3> poly) {
    std::vector<double> cdf;
    double total = 0;
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
        total += length(cross(poly[k] - poly[0], poly[k + 1] - poly[0]));
        cdf.push_back(total);
    }
    for (auto& c : cdf) c = total > 0 ? c / total : 1;
    return cdf;
}

// Keeps the part of `poly` on the positive side of the plane (point, normal).
std::vector<Vec3> clip_to_front(std::span<const Vec3> poly, const Vec3& point, const Vec3& normal) {
    std::vector<Vec3> out;
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3& a = poly[k];
        const Vec3& b = poly[(k + 1) % n];
        const double da = dot(a - point, normal), db = dot(b - point, normal);
        if (da >= 0) out.push_back(a);
        if ((da > 0 && db < 0) || (da < 0 && db > 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

Vec3 orthogonal(const Vec3& n) {
    return std::abs(n[0]) > 0.5 ? normalized(cross(n, Vec3{0, 1, 0}))
                                : normalized(cross(n, Vec3{1, 0, 0}));
}

// Radical inverse in base b: the Halton sequence, rotated per patch (Cranley-Patterson).
double radical_inverse(std::uint64_t i, std::uint64_t base) {
    double inv = 1.0 / base, f = inv, r = 0;
    while (i) {
        r += f * (i % base);
        i /= base;
        f *= inv;
    }
    return r;
}

double wrap(double x) {
    return x - std::floor(x);
}

} // namespace

FormFactorMethod parse_method(const std::string& name) {
    if (name == "pairwise") return FormFactorMethod::Pairwise;
    if (name == "analytic") return FormFactorMethod::Analytic;
    if (name == "hemisphere") return FormFactorMethod::Hemisphere;
    throw InputError("unknown form-factor method '" + name +
                     "' (use pairwise, analytic or hemisphere)");
}

std::string method_name(FormFactorMethod method) {
    switch (method) {
    case FormFactorMethod::Pairwise:
        return "pairwise";
    case FormFactorMethod::Analytic:
        return "analytic";
    case FormFactorMethod::Hemisphere:
        return "hemisphere";
    }
    return "?";
}

double point_to_polygon_form_factor(const Vec3& point, const Vec3& normal,
                                    std::span<const Vec3> polygon) {
    double sum = 0;
    const std::size_t n = polygon.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3 a = normalized(polygon[k] - point);
        const Vec3 b = normalized(polygon[(k + 1) % n] - point);
        const Vec3 c = cross(a, b);
        const double s = length(c);
        if (s < 1e-15) continue;
        const double angle = std::atan2(s, dot(a, b));
        sum += angle * dot(normal, c) / s;
    }
    return std::abs(sum) / (2 * kPi);
}

double parallel_rectangles_form_factor(double a, double b, double c) {
    const double x = a / c, y = b / c;
    const double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
    return 2 / (kPi * x * y) *
           (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
            x * y1 * std::atan(x / y1) + y * x1 * std::atan(y / x1) - x * std::atan(x) -
            y * std::atan(y));
}

double perpendicular_rectangles_form_factor(double h, double l, double w) {
    // From rectangle of width w (perpendicular to the common edge of length l) to the
    // rectangle of height h: H = h/l, W = w/l.
    const double H = h / l, W = w / l;
    const double H2 = H * H, W2 = W * W, HW = std::sqrt(H2 + W2);
    const double term = W * std::atan(1 / W) + H * std::atan(1 / H) - HW * std::atan(1 / HW) +
                        0.25 * std::log((1 + W2) * (1 + H2) / (1 + W2 + H2) *
                                        std::pow(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2)), W2) *
                                        std::pow(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)), H2));
    return term / (kPi * W);
}

std::uint64_t estimate_form_factor_memory(const radfmt::MeshData& mesh,
                                          const FormFactorOptions& options) {
    const std::uint64_t n = mesh.patches.size();
    const std::uint64_t per_row =
        options.method == FormFactorMethod::Hemisphere
            ? std::min<std::uint64_t>(n, static_cast<std::uint64_t>(options.rays))
            : n;
    // Rows are built then packed: entries (4 + 4 bytes) are held twice at the peak; Embree
    // and the mesh take a few hundred bytes per patch.
    return 2 * n * per_row * 8 + n * 400 + mesh.vertices.size() * 64;
}

radfmt::FormFactorData compute_form_factors(const radfmt::MeshData& mesh,
                                            const FormFactorOptions& options,
                                            FormFactorStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = mesh.patches.size();
    const RayScene scene(mesh);
    const double eps = scene.epsilon();
    std::vector<PatchGeometry> geometry;
    geometry.reserve(n);
    for (const auto& p : mesh.patches) geometry.push_back(patch_geometry(mesh, p));

    const int m =
        std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, options.samples)))));
    const int m_near = m, m_far = std::max(1, (m + 2) / 4);
    std::vector<double> diameter(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < geometry[i].count; ++a)
            for (int b = a + 1; b < geometry[i].count; ++b)
                diameter[i] =
                    std::max(diameter[i], length(geometry[i].corners[a] - geometry[i].corners[b]));
    std::vector<double> gl_nodes, gl_weights;
    gauss_legendre(m, gl_nodes, gl_weights);
    std::vector<double> gl_far_nodes, gl_far_weights, gl_close_nodes, gl_close_weights;
    gauss_legendre(2 * m, gl_close_nodes, gl_close_weights);
    gauss_legendre(m_far, gl_far_nodes, gl_far_weights);

    // Hemisphere: the low-discrepancy points are the same for every patch (only their
    // rotation differs), so they are computed once rather than per ray.
    std::vector<std::array<double, 4>> qmc;
    if (options.method == FormFactorMethod::Hemisphere) {
        const int k_rays = std::max(1, options.rays);
        qmc.resize(k_rays);
        for (int r = 0; r < k_rays; ++r)
            qmc[r] = {(r + 0.5) / k_rays, radical_inverse(r, 2), radical_inverse(r + 1, 3),
                      radical_inverse(r + 1, 5)};
    }

    struct HitTally {
        std::vector<std::uint32_t> counts; // hits per patch, all zero between rows
        std::vector<std::uint32_t> touched;
    };
    tbb::enumerable_thread_specific<HitTally> hit_tally;

    std::vector<std::vector<std::pair<std::uint32_t, float>>> rows(n);
    std::atomic<std::uint64_t> rays_cast{0};
    Progress progress("rad-ff " + method_name(options.method), n, options.quiet);

    // Does any corner of patch j lie strictly in front of patch i's plane?
    auto in_front = [&](std::size_t i, std::size_t j) {
        const auto& pi = mesh.patches[i];
        for (int k = 0; k < geometry[j].count; ++k)
            if (dot(geometry[j].corners[k] - pi.centroid, pi.normal) > eps) return true;
        return false;
    };

    auto compute_row = [&](std::size_t i) {
        Rng rng(options.seed, i);
        const auto& pi = mesh.patches[i];
        std::uint64_t local_rays = 0;
        auto& row = rows[i];
        if (options.method == FormFactorMethod::Hemisphere) {
            const int k_rays = std::max(1, options.rays);
            const auto& g = geometry[i];
            std::span<const Vec3> poly(g.corners.data(), g.count);
            const auto cdf = fan_cdf(poly);
            const Vec3 tu = orthogonal(pi.normal), tv = cross(pi.normal, tu);
            // Quasi-Monte Carlo: a 4D low-discrepancy set (Hammersley's (0,2)-net for the
            // origin, Halton bases 3 and 5 for the direction), rotated per patch by seeded
            // offsets (Cranley-Patterson), so the estimate is unbiased and stratified jointly.
            const double rot[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
            // Hits are tallied in a per-thread counter over all patches; only the distinct
            // patches hit are sorted (fewer than the rays), and the counter is reset after.
            auto& tally = hit_tally.local();
            if (tally.counts.size() != n) tally.counts.assign(n, 0);
            auto& hit_patches = tally.touched;
            hit_patches.clear();
            for (int r = 0; r < k_rays; ++r) {
                const double u0 = wrap(qmc[r][0] + rot[0]);
                const double u1 = wrap(qmc[r][1] + rot[1]);
                const double u2 = wrap(qmc[r][2] + rot[2]);
                const double u3 = wrap(qmc[r][3] + rot[3]);
                // Choose a fan triangle with u0, then reuse u0's remainder: stays stratified.
                double within = 0;
                const std::size_t tri = pick_fan_triangle(cdf, u0, &within);
                const Vec3 origin = fan_triangle_point(poly, tri, within, u1);
                // Cosine-weighted direction: Malley's method.
                const double radius = std::sqrt(u2), phi = 2 * kPi * u3;
                const Vec3 dir = tu * (radius * std::cos(phi)) + tv * (radius * std::sin(phi)) +
                                 pi.normal * std::sqrt(std::max(0.0, 1 - u2));
                bool front = false;
                const auto hit = scene.first_hit(origin, dir, front);
                ++local_rays;
                if (hit >= 0 && front && static_cast<std::size_t>(hit) != i &&
                    tally.counts[hit]++ == 0)
                    hit_patches.push_back(static_cast<std::uint32_t>(hit));
            }
            std::sort(hit_patches.begin(), hit_patches.end());
            row.reserve(hit_patches.size());
            for (const auto j : hit_patches) {
                row.emplace_back(j, static_cast<float>(double(tally.counts[j]) / k_rays));
                tally.counts[j] = 0;
            }
        } else {
            const auto samples_i = options.method == FormFactorMethod::Analytic
                                       ? gauss_samples(geometry[i], pi.area, gl_nodes, gl_weights)
                                       : gauss_samples(geometry[i], pi.area, gl_nodes, gl_weights);
            // Analytic: close pairs (the integrand varies fast near a shared edge) get twice
            // the points per axis.
            const auto samples_i_close =
                options.method == FormFactorMethod::Analytic
                    ? gauss_samples(geometry[i], pi.area, gl_close_nodes, gl_close_weights)
                    : std::vector<Sample>{};
            const auto samples_i_far =
                options.method == FormFactorMethod::Pairwise
                    ? gauss_samples(geometry[i], pi.area, gl_far_nodes, gl_far_weights)
                    : std::vector<Sample>{};
            for (std::size_t j = 0; j < n; ++j) {
                if (j == i || !in_front(i, j) || !in_front(j, i)) continue;
                const auto& pj = mesh.patches[j];
                std::span<const Vec3> poly_j(geometry[j].corners.data(), geometry[j].count);
                double f = 0;
                if (options.method == FormFactorMethod::Analytic) {
                    // Patch i is planar: clipping j to i's front half-space is the same for
                    // every sample point of i, so it is done once per pair.
                    const auto clipped = clip_to_front(poly_j, pi.centroid, pi.normal);
                    if (clipped.size() < 3) continue;
                    const auto cdf = fan_cdf(clipped);
                    const int vis = std::max(1, options.visibility_rays);
                    const bool close =
                        length(pj.centroid - pi.centroid) < 2 * std::max(diameter[i], diameter[j]);
                    for (const auto& s : close ? samples_i_close : samples_i) {
                        // Visible fraction from this point: rays to area-uniform points of j,
                        // weighted by the kernel cos cos / r^2 so that the parts of j that
                        // matter most count most (exact when all or none are visible).
                        double seen = 0, total = 0;
                        for (int r = 0; r < vis; ++r) {
                            const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
                            const Vec3 y = uniform_point(clipped, cdf, u0, u1, u2);
                            const Vec3 d = y - s.point;
                            const double r2 = dot(d, d);
                            const double kernel = vis == 1 ? 1.0
                                                           : std::max(0.0, dot(d, pi.normal)) *
                                                                 std::max(0.0, -dot(d, pj.normal)) /
                                                                 (r2 * r2 + 1e-300);
                            total += kernel;
                            if (scene.visible(s.point, y)) seen += kernel;
                        }
                        local_rays += vis;
                        if (seen > 0)
                            f += s.weight * (total > 0 ? seen / total : 0.0) *
                                 point_to_polygon_form_factor(s.point, pi.normal, clipped);
                    }
                } else {
                    // Pairwise: eq. 5 by sample pairs: Gauss-Legendre points on i, and on j an
                    // m x m grid of cells, each standing for its own area. Each sample of j stands
                    // for its cell of j's m x m grid; the cell's form factor from the point of i is
                    // taken in closed form, which keeps adjacent pairs finite as r -> 0, and one
                    // ray per pair decides whether the cell is visible. Far pairs have a smooth
                    // integrand: a quarter of the resolution suffices.
                    const auto& gj = geometry[j];
                    const bool far =
                        length(pj.centroid - pi.centroid) > 4 * std::max(diameter[i], diameter[j]);
                    const int m = far ? m_far : m_near;
                    for (const auto& s : far ? samples_i_far : samples_i) {
                        for (int a = 0; a < m; ++a)
                            for (int b = 0; b < m; ++b) {
                                double jac = 0;
                                std::array<Vec3, 4> cell{
                                    patch_point(gj, double(a) / m, double(b) / m, jac),
                                    patch_point(gj, double(a + 1) / m, double(b) / m, jac),
                                    patch_point(gj, double(a + 1) / m, double(b + 1) / m, jac),
                                    patch_point(gj, double(a) / m, double(b + 1) / m, jac)};
                                const auto clipped = clip_to_front(cell, s.point, pi.normal);
                                if (clipped.size() < 3) continue;
                                const Vec3 target = patch_point(gj, (a + rng.uniform()) / m,
                                                                (b + rng.uniform()) / m, jac);
                                if (dot(target - s.point, pi.normal) <= 0) continue;
                                ++local_rays;
                                if (!scene.visible(s.point, target)) continue;
                                f += s.weight *
                                     point_to_polygon_form_factor(s.point, pi.normal, clipped);
                            }
                    }
                }
                if (f > 0) row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(f));
            }
        }
        rays_cast += local_rays;
        progress.advance(1);
    };
    const auto trace_start = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) compute_row(i);
                      });
    const double trace_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - trace_start).count();
    progress.finish();

    radfmt::FormFactorData ff;
    ff.patch_count = n;
    ff.row_start.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ff.row_start[i + 1] = ff.row_start[i] + rows[i].size();
    ff.columns.reserve(ff.row_start[n]);
    ff.values.reserve(ff.row_start[n]);
    double sum_rows = 0, max_row = 0;
    for (auto& row : rows) {
        double sum = 0;
        for (const auto& [col, value] : row) {
            ff.columns.push_back(col);
            ff.values.push_back(value);
            sum += value;
        }
        sum_rows += sum;
        max_row = std::max(max_row, sum);
        std::vector<std::pair<std::uint32_t, float>>().swap(row);
    }
    if (stats) {
        stats->rays_cast = rays_cast;
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->trace_seconds = trace_seconds;
        stats->mean_row_sum = n ? sum_rows / n : 0;
        stats->max_row_sum = max_row;
    }
    return ff;
}

} // namespace rad
