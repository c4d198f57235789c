// pairwise: the paper's double integral of eq. 5 by sample pairs: Gauss-Legendre points on
// patch i against an m x m grid of cells on patch j, each cell's form factor from the point
// taken in closed form, one ray per pair for visibility.
#include "sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rad::ff {
namespace {

// Patch j's m x m cells as a grid of (m + 1)^2 points, seen from one sample point of i at a
// time. A cell wholly in front of the sample's plane takes its form factor from its four
// edges' contour terms, each computed once and shared with the neighbouring cell (walked
// the other way, exactly negated): half the arctangents of a cell at a time, the same sum
// in the same order, so the same bits. Other cells are clipped and summed whole.
class CellGrid {
  public:
    void set_patch(const PatchPolygon& patch, int m) {
        m_ = m;
        points_.clear();
        for (int b = 0; b <= m; ++b)
            for (int a = 0; a <= m; ++a) {
                double jac = 0;
                points_.push_back(patch_point(patch, double(a) / m, double(b) / m, jac));
            }
    }
    void set_sample(const Vec3& point, const Vec3& normal) {
        normal_ = normal;
        direction_.resize(points_.size());
        height_.resize(points_.size());
        for (std::size_t k = 0; k < points_.size(); ++k) {
            direction_[k] = normalized(points_[k] - point);
            height_[k] = dot(points_[k] - point, normal);
        }
        along_a_.assign(points_.size(), kUnknown);
        along_b_.assign(points_.size(), kUnknown);
    }
    // Cell (a, b)'s corners, counter-clockwise as the patch's.
    std::array<Vec3, 4> cell(int a, int b) const {
        return {points_[at(a, b)], points_[at(a + 1, b)], points_[at(a + 1, b + 1)],
                points_[at(a, b + 1)]};
    }
    bool in_front(int a, int b) const {
        return height_[at(a, b)] >= 0 && height_[at(a + 1, b)] >= 0 &&
               height_[at(a + 1, b + 1)] >= 0 && height_[at(a, b + 1)] >= 0;
    }
    // The form factor from the sample to cell (a, b), which must be in front.
    double form_factor(int a, int b) {
        double sum = 0;
        sum += edge_along_a(a, b);
        sum += edge_along_b(a + 1, b);
        sum += -edge_along_a(a, b + 1);
        sum += -edge_along_b(a, b);
        return std::abs(sum) / (2 * kPi);
    }

  private:
    static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    std::size_t at(int a, int b) const { return std::size_t(b) * std::size_t(m_ + 1) + a; }
    // The edges from point (a, b) to (a + 1, b) and to (a, b + 1).
    double edge_along_a(int a, int b) { return edge(along_a_, at(a, b), at(a + 1, b)); }
    double edge_along_b(int a, int b) { return edge(along_b_, at(a, b), at(a, b + 1)); }
    // The term of the edge from point `from` to point `to`, kept in `terms[from]`.
    double edge(std::vector<double>& terms, std::size_t from, std::size_t to) {
        if (std::isnan(terms[from]))
            terms[from] = contour_edge_term(direction_[from], direction_[to], normal_);
        return terms[from];
    }
    int m_ = 1;
    Vec3 normal_{};
    std::vector<Vec3> points_, direction_;
    std::vector<double> height_, along_a_, along_b_;
};

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
        CellGrid grid; // j's m x m cells
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
            const auto& sample_points = far ? samples_far : samples;
            double f = 0;
            // A polygon is the sum of its fan's triangles, each with its own grid of cells.
            if (gj.is_polygon())
                for (const auto& triangle : fan_triangles(gj))
                    f += cells_form_factor(triangle, m, sample_points, pi, grid, rng, rays);
            else
                f = cells_form_factor(gj, m, sample_points, pi, grid, rng, rays);
            if (f > 0) row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(f));
        }
        return rays;
    }

  private:
    // The form factor from i's `samples` to patch (or part) g's m x m cells, one ray each.
    double cells_form_factor(const PatchPolygon& g, int m, std::span<const Sample> samples,
                             const radfmt::Patch& pi, CellGrid& grid, Rng& rng,
                             std::uint64_t& rays) const {
        std::vector<Vec3> clipped; // a cell's part in front of i's sample
        grid.set_patch(g, m);
        double f = 0;
        for (const auto& s : samples) {
            grid.set_sample(s.point, pi.normal);
            for (int a = 0; a < m; ++a)
                for (int b = 0; b < m; ++b) {
                    const bool whole = grid.in_front(a, b);
                    if (!whole) {
                        clip_to_front(grid.cell(a, b), s.point, pi.normal, clipped);
                        if (clipped.size() < 3) continue;
                    }
                    double jac = 0;
                    const Vec3 target =
                        patch_point(g, (a + rng.uniform()) / m, (b + rng.uniform()) / m, jac);
                    if (dot(target - s.point, pi.normal) <= 0) continue;
                    ++rays;
                    if (!context_.scene.visible(s.point, target)) continue;
                    f += s.weight *
                         (whole ? grid.form_factor(a, b)
                                : point_to_polygon_form_factor(s.point, pi.normal, clipped));
                }
        }
        return f;
    }

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
