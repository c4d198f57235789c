// pairwise: the paper's double integral of eq. 5 by sample pairs: Gauss-Legendre points on
// patch i against an m x m grid of cells on patch j, each cell's form factor from the point
// taken in closed form, one ray per pair for visibility.
#include "sampling.hpp"

#include <algorithm>

namespace rad::ff {
namespace {

class PairwiseKernel final : public RowKernel {
  public:
    PairwiseKernel(const FormFactorContext& context, const FormFactorOptions& options)
        : context_(context) {
        m_near_ = points_per_axis(options.samples);
        m_far_ = std::max(1, (m_near_ + 2) / 4);
        gauss_legendre(m_near_, nodes_, weights_);
        gauss_legendre(m_far_, far_nodes_, far_weights_);
    }

    std::uint64_t compute_row(std::size_t i, Rng& row_rng, FormFactorRow& row,
                              RayLog&) const override {
        const auto& mesh = context_.mesh;
        const auto& pi = mesh.patches[i];
        const auto samples = gauss_samples(context_.polygons[i], pi.area, nodes_, weights_);
        const auto samples_far =
            gauss_samples(context_.polygons[i], pi.area, far_nodes_, far_weights_);
        std::uint64_t rays = 0;
        // Each pair draws from a stream of its own: F_ij does not depend on which other
        // patches come before j.
        const std::uint64_t row_seed = row_rng.next();
        const std::size_t n = mesh.patches.size();
        std::vector<std::array<Vec3, 4>> cells; // j's m x m cells
        std::vector<Vec3> clipped;              // a cell's part in front of i's sample
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i || !context_.in_front(i, j) || !context_.in_front(j, i)) continue;
            const auto& pj = mesh.patches[j];
            Rng rng(row_seed, context_.stream_key[j]);
            const auto& gj = context_.polygons[j];
            // Each sample of j stands for its cell of j's m x m grid; the cell's form factor
            // from the point of i is taken in closed form, which keeps adjacent pairs finite
            // as r -> 0. Far pairs have a smooth integrand: a quarter of the resolution
            // suffices.
            const bool far = length(pj.centroid - pi.centroid) >
                             4 * std::max(context_.diameter[i], context_.diameter[j]);
            const int m = far ? m_far_ : m_near_;
            // j's cells depend on neither the sample of i nor the random numbers: made once
            // per pair of patches, not once per sample.
            cells.clear();
            for (int a = 0; a < m; ++a)
                for (int b = 0; b < m; ++b) {
                    double jac = 0;
                    cells.push_back({patch_point(gj, double(a) / m, double(b) / m, jac),
                                     patch_point(gj, double(a + 1) / m, double(b) / m, jac),
                                     patch_point(gj, double(a + 1) / m, double(b + 1) / m, jac),
                                     patch_point(gj, double(a) / m, double(b + 1) / m, jac)});
                }
            double f = 0;
            for (const auto& s : far ? samples_far : samples) {
                for (int a = 0; a < m; ++a)
                    for (int b = 0; b < m; ++b) {
                        clip_to_front(cells[std::size_t(a * m + b)], s.point, pi.normal, clipped);
                        if (clipped.size() < 3) continue;
                        double jac = 0;
                        const Vec3 target =
                            patch_point(gj, (a + rng.uniform()) / m, (b + rng.uniform()) / m, jac);
                        if (dot(target - s.point, pi.normal) <= 0) continue;
                        ++rays;
                        if (!context_.scene.visible(s.point, target)) continue;
                        f += s.weight * point_to_polygon_form_factor(s.point, pi.normal, clipped);
                    }
            }
            if (f > 0) row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(f));
        }
        return rays;
    }

  private:
    const FormFactorContext& context_;
    int m_near_ = 1, m_far_ = 1;
    std::vector<double> nodes_, weights_, far_nodes_, far_weights_;
};

class Pairwise final : public FormFactorMethod {
  public:
    std::string_view name() const override { return "pairwise"; }
    std::string_view summary() const override {
        return "the paper's point-pair integration of eq. 5 (slow; a reference)";
    }
    void apply_defaults(FormFactorOptions& options) const override {
        if (options.samples == 0) options.samples = 64;
    }
    std::vector<std::pair<std::string, std::string>>
    header_fields(const FormFactorOptions& options) const override {
        return {{"samples", std::to_string(options.samples)}};
    }
    std::unique_ptr<RowKernel> prepare(const FormFactorContext& context,
                                       const FormFactorOptions& options) const override {
        return std::make_unique<PairwiseKernel>(context, options);
    }
};

} // namespace

const FormFactorMethod& pairwise_method() {
    static const Pairwise method;
    return method;
}

} // namespace rad::ff
