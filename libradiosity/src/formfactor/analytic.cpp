// analytic: at Gauss-Legendre points of patch i, the exact point-to-polygon form factor of
// patch j (clipped to i's front) times the ray-estimated visible fraction of j.
#include "sampling.hpp"

#include <algorithm>

namespace rad::ff {
namespace {

class AnalyticKernel final : public RowKernel {
  public:
    AnalyticKernel(const FormFactorContext& context, const FormFactorOptions& options)
        : context_(context), visibility_rays_(std::max(1, options.visibility_rays)) {
        const int m = points_per_axis(options.samples);
        gauss_legendre(m, nodes_, weights_);
        gauss_legendre(2 * m, close_nodes_, close_weights_);
    }

    std::uint64_t compute_row(std::size_t i, Rng& row_rng, FormFactorRow& row,
                              RayLog&) const override {
        const auto& mesh = context_.mesh;
        const auto& pi = mesh.patches[i];
        const auto samples = gauss_samples(context_.polygons[i], pi.area, nodes_, weights_);
        // Close pairs (the integrand varies fast near a shared edge) get twice the points
        // per axis.
        const auto samples_close =
            gauss_samples(context_.polygons[i], pi.area, close_nodes_, close_weights_);
        std::uint64_t rays = 0;
        // Each pair draws from a stream of its own: F_ij does not depend on which other
        // patches come before j.
        const std::uint64_t row_seed = row_rng.next();
        const std::size_t n = mesh.patches.size();
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i || !context_.in_front(i, j) || !context_.in_front(j, i)) continue;
            const auto& pj = mesh.patches[j];
            Rng rng(row_seed, context_.stream_key[j]);
            // Patch i is planar: clipping j to i's front half-space is the same for every
            // sample point of i, so it is done once per pair.
            const auto clipped =
                clip_to_front(context_.polygons[j].points(), pi.centroid, pi.normal);
            if (clipped.size() < 3) continue;
            const auto cdf = fan_cdf(clipped);
            const int vis = visibility_rays_;
            const bool close = length(pj.centroid - pi.centroid) <
                               2 * std::max(context_.diameter[i], context_.diameter[j]);
            double f = 0;
            for (const auto& s : close ? samples_close : samples) {
                // Visible fraction from this point: rays to area-uniform points of j,
                // weighted by the kernel cos cos / r^2 so that the parts of j that matter
                // most count most (exact when all or none are visible).
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
                    if (context_.scene.visible(s.point, y)) seen += kernel;
                }
                rays += vis;
                if (seen > 0)
                    f += s.weight * (total > 0 ? seen / total : 0.0) *
                         point_to_polygon_form_factor(s.point, pi.normal, clipped);
            }
            if (f > 0) row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(f));
        }
        return rays;
    }

  private:
    const FormFactorContext& context_;
    int visibility_rays_;
    std::vector<double> nodes_, weights_, close_nodes_, close_weights_;
};

class Analytic final : public FormFactorMethod {
  public:
    std::string_view name() const override { return "analytic"; }
    std::string_view summary() const override {
        return "exact point-to-polygon integral x ray visibility (default; O(n^2))";
    }
    void apply_defaults(FormFactorOptions& options) const override {
        if (options.samples == 0) options.samples = 16;
    }
    std::vector<std::pair<std::string, std::string>>
    header_fields(const FormFactorOptions& options) const override {
        return {{"samples", std::to_string(options.samples)},
                {"visibility_rays", std::to_string(options.visibility_rays)}};
    }
    std::unique_ptr<RowKernel> prepare(const FormFactorContext& context,
                                       const FormFactorOptions& options) const override {
        return std::make_unique<AnalyticKernel>(context, options);
    }
};

} // namespace

const FormFactorMethod& analytic_method() {
    static const Analytic method;
    return method;
}

} // namespace rad::ff
