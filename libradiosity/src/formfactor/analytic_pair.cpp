// analytic_pair_form_factor: analytic's rule for one pair of patches, shared with the
// hierarchical method's links between two patches.
#include "sampling.hpp"

#include <algorithm>

namespace rad::ff {

namespace {
// The rule for `part` of patch j, convex (j itself, or a triangle of a polygon's fan).
double convex_part_form_factor(const FormFactorContext& context, std::size_t i, std::size_t j,
                               std::span<const Vec3> part, std::span<const Sample> samples,
                               std::span<const Sample> samples_close, int visibility_rays, Rng& rng,
                               std::uint64_t& rays) {
    const auto& pi = context.mesh.patches[i];
    const auto& pj = context.mesh.patches[j];
    // Patch i is planar: clipping j to i's front half-space is the same for every sample
    // point of i, so it is done once per pair.
    const auto clipped = clip_to_front(part, pi.centroid, pi.normal);
    if (clipped.size() < 3) return 0;
    const auto cdf = fan_cdf(clipped);
    const int vis = visibility_rays;
    const bool close =
        length(pj.centroid - pi.centroid) < 2 * std::max(context.diameter[i], context.diameter[j]);
    double f = 0;
    for (const auto& s : close ? samples_close : samples) {
        // A point of i behind j's plane sees j's back (i crosses j's plane): nothing.
        if (dot(s.point - pj.centroid, pj.normal) <= 0) continue;
        // Visible fraction from this point: rays to area-uniform points of j, weighted by
        // the kernel cos cos / r^2 so that the parts of j that matter most count most (exact
        // when all or none are visible).
        double seen = 0, total = 0;
        for (int r = 0; r < vis; ++r) {
            const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            const Vec3 y = uniform_point(clipped, cdf, u0, u1, u2);
            const Vec3 d = y - s.point;
            const double r2 = dot(d, d);
            const double kernel = vis == 1
                                      ? 1.0
                                      : std::max(0.0, dot(d, pi.normal)) *
                                            std::max(0.0, -dot(d, pj.normal)) / (r2 * r2 + 1e-300);
            total += kernel;
            if (context.scene.visible(s.point, y)) seen += kernel;
        }
        rays += vis;
        if (seen > 0)
            f += s.weight * (total > 0 ? seen / total : 0.0) *
                 point_to_polygon_form_factor(s.point, pi.normal, clipped);
    }
    return f;
}
} // namespace

double analytic_pair_form_factor(const FormFactorContext& context, std::size_t i, std::size_t j,
                                 std::span<const Sample> samples,
                                 std::span<const Sample> samples_close, int visibility_rays,
                                 Rng& rng, std::uint64_t& rays) {
    if (!context.in_front(i, j) || !context.in_front(j, i)) return 0;
    const auto& gj = context.polygons[j];
    if (!gj.is_polygon())
        return convex_part_form_factor(context, i, j, gj.points(), samples, samples_close,
                                       visibility_rays, rng, rays);
    // A polygon need not be convex, and clipped it need not be star-shaped: its fan's
    // triangles are summed, each clipped and sampled for visibility on its own.
    double f = 0;
    for (const auto& triangle : fan_triangles(gj))
        f += convex_part_form_factor(context, i, j, triangle.points(), samples, samples_close,
                                     visibility_rays, rng, rays);
    return f;
}

} // namespace rad::ff
