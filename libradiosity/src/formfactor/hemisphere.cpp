// hemisphere: K cosine-weighted rays per patch from area-uniform origins (quasi-Monte
// Carlo); F_ij = hits on j's front / K. Scales to large scenes.
#include "sampling.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>

namespace rad::ff {
namespace {

class HemisphereKernel final : public RowKernel {
  public:
    HemisphereKernel(const FormFactorContext& context, const FormFactorOptions& options)
        : context_(context), rays_(std::max(1, options.rays)) {
        // The low-discrepancy points are the same for every patch (only their rotation
        // differs), so they are computed once rather than per ray.
        qmc_.resize(rays_);
        for (int r = 0; r < rays_; ++r)
            qmc_[r] = {(r + 0.5) / rays_, radical_inverse(r, 2), radical_inverse(r + 1, 3),
                       radical_inverse(r + 1, 5)};
    }

    std::uint64_t compute_row(std::size_t i, Rng& rng, FormFactorRow& row,
                              RayLog& log) const override {
        const auto& mesh = context_.mesh;
        const auto& pi = mesh.patches[i];
        const std::size_t n = mesh.patches.size();
        const auto poly = context_.polygons[i].points();
        const auto cdf = fan_cdf(poly);
        const Vec3 tu = orthogonal(pi.normal), tv = cross(pi.normal, tu);
        // Quasi-Monte Carlo: a 4D low-discrepancy set (Hammersley's (0,2)-net for the
        // origin, Halton bases 3 and 5 for the direction), rotated per patch by seeded
        // offsets (Cranley-Patterson), so the estimate is unbiased and stratified jointly.
        const double rot[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
        if (context_.specular.any()) return specular_row(i, rot, poly, cdf, tu, tv, row, log);
        // Front hits are tallied in a dense array of this thread's (4 bytes a patch, so it
        // stays in the cache where the log's counters would not), the patches hit marked,
        // read back in column order, added to the log's front counts and reset.
        auto& hits = hits_.local();
        hits.resize(n);
        for (int r = 0; r < rays_; ++r) {
            const auto [origin, dir] = ray_of(i, r, rot, poly, cdf, tu, tv);
            const auto traced = context_.scene.trace(origin, dir);
            const auto hit = traced.patch;
            const bool front = traced.front;
            // A patch cannot see itself; a hit on itself (a warped quad) is no evidence.
            const bool self = static_cast<std::size_t>(hit) == i;
            if (hit >= 0 && front && !self) {
                log.record_counted_front();
                hits.add(static_cast<std::size_t>(hit), 1);
            } else {
                log.record(self ? -1 : hit, front, traced.distance);
            }
        }
        hits.drain([&](std::size_t j, std::uint32_t count) {
            row.emplace_back(static_cast<std::uint32_t>(j),
                             static_cast<float>(double(count) / rays_));
            log.add_fronts(j, count);
        });
        return static_cast<std::uint64_t>(rays_);
    }

  private:
    // Ray r's origin and direction from patch i (its quasi-Monte Carlo point, rotated).
    std::pair<Vec3, Vec3> ray_of(std::size_t i, int r, const double (&rot)[4],
                                 std::span<const Vec3> poly, std::span<const double> cdf,
                                 const Vec3& tu, const Vec3& tv) const {
        const auto& pi = context_.mesh.patches[i];
        const double u0 = wrap(qmc_[r][0] + rot[0]);
        const double u1 = wrap(qmc_[r][1] + rot[1]);
        const double u2 = wrap(qmc_[r][2] + rot[2]);
        const double u3 = wrap(qmc_[r][3] + rot[3]);
        // Choose a fan triangle with u0, then reuse u0's remainder: stays stratified.
        double within = 0;
        const std::size_t tri = pick_fan_triangle(cdf, u0, &within);
        return {fan_triangle_point(poly, tri, within, u1),
                cosine_direction(pi.normal, tu, tv, u2, u3)};
    }

    // The row of a mesh with mirrors or glass: each ray goes on through them (the extended
    // form factor of the two-pass method), and every surface it reaches on the way adds the
    // path's weight (the channels' mean) to F_ij. The same rays as without them.
    std::uint64_t specular_row(std::size_t i, const double (&rot)[4], std::span<const Vec3> poly,
                               std::span<const double> cdf, const Vec3& tu, const Vec3& tv,
                               FormFactorRow& row, RayLog& log) const {
        auto& sums = weights_.local();
        sums.resize(context_.mesh.patches.size());
        for (int r = 0; r < rays_; ++r) {
            const auto [origin, dir] = ray_of(i, r, rot, poly, cdf, tu, tv);
            bool met = false;
            follow_specular(context_.scene, context_.specular, origin, dir, radfmt::Rgb{{1, 1, 1}},
                            context_.specular_depth, [&](const PathHit& h) {
                                const auto j = static_cast<std::size_t>(h.hit.patch);
                                if (h.events == 0) {
                                    met = true;
                                    // Glass is met from behind as often as from the front.
                                    const bool front =
                                        h.hit.front || context_.specular.transmits(j);
                                    log.record(j == i ? -1 : h.hit.patch, front, h.hit.distance);
                                    if (j == i) return; // a warped quad: no evidence
                                }
                                if (!h.hit.front) return; // a diffuse part shines from its front
                                const double w = (h.weight[0] + h.weight[1] + h.weight[2]) / 3;
                                sums.add(j, w);
                            });
            if (!met) log.record(-1, false);
        }
        sums.drain([&](std::size_t j, double sum) {
            row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(sum / rays_));
        });
        return static_cast<std::uint64_t>(rays_);
    }

    const FormFactorContext& context_;
    int rays_;
    std::vector<std::array<double, 4>> qmc_;
    mutable tbb::enumerable_thread_specific<RowTally<std::uint32_t>> hits_; // front hits
    mutable tbb::enumerable_thread_specific<RowTally<double>> weights_;     // paths' weights
};

class Hemisphere final : public FormFactorMethod {
  public:
    std::string_view name() const override { return "hemisphere"; }
    std::string_view summary() const override {
        return "cosine-weighted rays per patch, F_ij = hits/rays (scales to large scenes)";
    }
    void apply_defaults(FormFactorOptions&) const override {} // --rays has its default
    bool logs_rays() const override { return true; }
    bool follows_specular() const override { return true; }
    std::vector<std::pair<std::string, std::string>>
    header_fields(const FormFactorOptions& options) const override {
        return {{"rays", std::to_string(options.rays)}};
    }
    std::uint64_t max_row_entries(const radfmt::MeshData& mesh,
                                  const FormFactorOptions& options) const override {
        // A path through mirrors and glass reaches several surfaces.
        if (mesh.has_specular()) return mesh.patches.size();
        return std::min<std::uint64_t>(mesh.patches.size(),
                                       static_cast<std::uint64_t>(std::max(1, options.rays)));
    }
    std::uint64_t working_memory(const radfmt::MeshData& mesh, const FormFactorOptions& options,
                                 unsigned threads) const override {
        // The shared low-discrepancy table (four doubles per ray), and per thread the row's
        // hit counts and the bitmaps of the patches hit.
        const std::uint64_t rays = static_cast<std::uint64_t>(std::max(1, options.rays));
        // (A mesh with mirrors or glass sums the paths' weights in doubles instead.)
        const std::uint64_t per_patch = mesh.has_specular() ? 8 : 4;
        return rays * sizeof(std::array<double, 4>) +
               std::uint64_t(threads) *
                   (mesh.patches.size() * per_patch + mesh.patches.size() / 8 + 1);
    }
    std::unique_ptr<RowKernel> prepare(const FormFactorContext& context,
                                       const FormFactorOptions& options) const override {
        return std::make_unique<HemisphereKernel>(context, options);
    }
};

} // namespace

const FormFactorMethod& hemisphere_method() {
    static const Hemisphere method;
    return method;
}

} // namespace rad::ff
