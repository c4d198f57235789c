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
        const std::uint64_t row_seed = row_rng.next();
        const std::size_t n = mesh.patches.size();
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) continue;
            // Each pair draws from a stream of its own: F_ij does not depend on which other
            // patches come before j.
            Rng rng(row_seed, context_.stream_key[j]);
            const double f = analytic_pair_form_factor(context_, i, j, samples, samples_close,
                                                       visibility_rays_, rng, rays);
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
