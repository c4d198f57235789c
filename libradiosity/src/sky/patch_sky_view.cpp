// rad-ff --sky: each patch's view of every sky patch and of the ground, by the hemisphere
// method's rays, each followed through mirrors and glass until it leaves the scene.
#include "formfactor/sampling.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/patch_geometry.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/random.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numbers>

namespace rad {
namespace {

// The quasi-Monte Carlo points of the hemisphere method: Hammersley for the origin, Halton 3
// and 5 for the direction; rotated per patch (Cranley-Patterson).
std::vector<std::array<double, 4>> qmc_points(int rays) {
    std::vector<std::array<double, 4>> out(static_cast<std::size_t>(rays));
    for (int r = 0; r < rays; ++r)
        out[std::size_t(r)] = {(r + 0.5) / rays, ff::radical_inverse(std::uint64_t(r), 2),
                               ff::radical_inverse(std::uint64_t(r) + 1, 3),
                               ff::radical_inverse(std::uint64_t(r) + 1, 5)};
    return out;
}

// One patch's row: D_is for every sky patch s; returns the paths that left the scene.
std::uint64_t sky_row(const radfmt::MeshData& mesh, std::size_t i, const RayScene& scene,
                      const SpecularSurfaces& specular, const SkyViewOptions& options,
                      const std::vector<std::array<double, 4>>& qmc, std::span<Rgb> row) {
    const auto& patch = mesh.patches[i];
    const auto poly = patch_points(mesh, i);
    const auto cdf = ff::fan_cdf(poly);
    const Vec3 tu = orthogonal(patch.normal), tv = cross(patch.normal, tu);
    Rng rng(options.seed, i);
    const double rot[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
    const double share = std::numbers::pi / double(qmc.size());
    std::uint64_t escaped = 0;
    for (const auto& q : qmc) {
        double within = 0;
        const auto tri = ff::pick_fan_triangle(cdf, ff::wrap(q[0] + rot[0]), &within);
        const Vec3 origin = ff::fan_triangle_point(poly, tri, within, ff::wrap(q[1] + rot[1]));
        const Vec3 d = cosine_direction(patch.normal, tu, tv, ff::wrap(q[2] + rot[2]),
                                        ff::wrap(q[3] + rot[3]));
        follow_specular(
            scene, specular, origin, d, Rgb{{1, 1, 1}}, options.specular_depth,
            [](const PathHit&) {},
            [&](const Vec3& out, const Rgb& w) {
                auto& c = row[options.patches.patch_of(options.frame, out)];
                for (int k = 0; k < 3; ++k) c[std::size_t(k)] += share * w[std::size_t(k)];
                ++escaped;
            });
    }
    return escaped;
}
} // namespace

std::vector<Rgb> patch_sky_view(const radfmt::MeshData& mesh, const RayScene& scene,
                                const SpecularSurfaces& specular, const SkyViewOptions& options,
                                std::uint64_t begin, std::uint64_t end, SkyViewStats* stats,
                                bool quiet) {
    const auto start = std::chrono::steady_clock::now();
    end = std::min<std::uint64_t>(end, mesh.patches.size());
    begin = std::min(begin, end);
    const std::size_t count = options.patches.count();
    std::vector<Rgb> out((end - begin) * count, Rgb{});
    const auto qmc = qmc_points(std::max(1, options.rays));
    std::atomic<std::uint64_t> escaped{0};
    Progress progress("rad-ff sky", end - begin, quiet);
    tbb::parallel_for(begin, end, [&](std::uint64_t i) {
        escaped += sky_row(mesh, i, scene, specular, options, qmc,
                           std::span<Rgb>(out).subspan((i - begin) * count, count));
        progress.advance(1);
    });
    progress.finish();
    if (stats) {
        stats->rays = (end - begin) * qmc.size();
        stats->escaped = escaped;
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return out;
}

double sensor_sun(const RayScene& scene, const SpecularSurfaces& specular, int depth,
                  const Vec3& point, const Vec3& normal, const Vec3& sun_direction,
                  double normal_illuminance, const PlanarMirrors* mirrors) {
    if (normal_illuminance <= 0 || sun_direction[1] <= 0) return 0;
    // Within the sun's disc: half of 0.533 degrees.
    const double disc = std::cos(0.2665 * std::numbers::pi / 180);
    // The beam along `d` from the point: what of it leaves the scene toward the sun (through
    // glass straight, off a mirror once when d is the sun's image in it), by cos to the normal.
    const auto along = [&](const Vec3& d) {
        const double cosine = dot(d, normal);
        if (cosine <= 0) return 0.0;
        double through = 0;
        follow_specular(
            scene, specular, point, d, Rgb{{1, 1, 1}}, depth, [](const PathHit&) {},
            [&](const Vec3& out, const Rgb& w) {
                if (dot(out, sun_direction) >= disc) through += luminous(w);
            });
        return cosine * through;
    };
    double sum = along(sun_direction);
    // The sun's image in each planar mirror it shines on (a virtual source, as the lamps'):
    // the direction it is seen in, once for parallel mirrors (an earlier plane that gives the
    // same image has counted it; no list is kept, this runs per sensor and hour).
    if (!mirrors) return normal_illuminance * sum;
    const auto image = [&](std::size_t k, Vec3& d) {
        if (!(dot(sun_direction, mirrors->planes[k].normal) > 0)) return false;
        d = mirrors->mirrored_direction(k, sun_direction);
        return true;
    };
    for (std::size_t k = 0; k < mirrors->planes.size(); ++k) {
        Vec3 d, e;
        if (!image(k, d)) continue;
        bool counted = false;
        for (std::size_t j = 0; j < k && !counted; ++j)
            counted = image(j, e) && dot(e, d) > 1 - 1e-12;
        if (!counted) sum += along(d);
    }
    return normal_illuminance * sum;
}

} // namespace rad
