// hemisphere: K cosine-weighted rays per patch from area-uniform origins (quasi-Monte
// Carlo); F_ij = hits on j's front / K. Scales to large scenes.
#include "sampling.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>

namespace rad::ff {
namespace {

class HemisphereKernel final : public RowKernel {
  public:
    HemisphereKernel(const FormFactorContext& context, const FormFactorOptions& options)
        : context_(context), rays_(std::max(1, options.rays)),
          batches_(std::max(0, options.error_batches)) {
        // The low-discrepancy points are the same for every patch (only their rotation
        // differs), so they are computed once rather than per ray. In batches, each batch is
        // one such set of rays / batches points.
        const int points = batches_ > 0 ? rays_ / batches_ : rays_;
        qmc_.resize(points);
        for (int r = 0; r < points; ++r)
            qmc_[r] = {(r + 0.5) / points, radical_inverse(r, 2), radical_inverse(r + 1, 3),
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
        if (batches_ > 0) return batched_row(i, rng, poly, cdf, tu, tv, row, log);
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
            follow_paths(i, origin, dir, log, [&](std::size_t j, double w) { sums.add(j, w); });
        }
        sums.drain([&](std::size_t j, double sum) {
            row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(sum / rays_));
        });
        return static_cast<std::uint64_t>(rays_);
    }

    // One ray's path on through mirrors and glass: reach(j, weight) for each surface whose
    // diffuse front it reaches on the way.
    template <class Reach>
    void follow_paths(std::size_t i, const Vec3& origin, const Vec3& dir, RayLog& log,
                      Reach&& reach) const {
        bool met = false;
        follow_specular(context_.scene, context_.specular, origin, dir, radfmt::Rgb{{1, 1, 1}},
                        context_.specular_depth, [&](const PathHit& h) {
                            const auto j = static_cast<std::size_t>(h.hit.patch);
                            if (h.events == 0) {
                                met = true;
                                // Glass is met from behind as often as from the front.
                                const bool front = h.hit.front || context_.specular.transmits(j);
                                log.record(j == i ? -1 : h.hit.patch, front, h.hit.distance);
                                if (j == i) return; // a warped quad: no evidence
                            }
                            if (!h.hit.front) return; // a diffuse part shines from its front
                            reach(j, (h.weight[0] + h.weight[1] + h.weight[2]) / 3);
                        });
        if (!met) log.record(-1, false);
    }

    // The row cast as independent batches (each its own rotation of the stratified set), and
    // its standard error from them. With p_bj batch b's estimate of F_ij and p_j their mean,
    // sum_j sum_b (p_bj - p_j)^2 / (B (B - 1)) is an unbiased estimate of the sum of the
    // entries' variances (the batches are i.i.d. and unbiased); its square root is the row's
    // error. The strata of one set are not independent, so rays one by one would not do.
    std::uint64_t batched_row(std::size_t i, Rng& rng, std::span<const Vec3> poly,
                              std::span<const double> cdf, const Vec3& tu, const Vec3& tv,
                              FormFactorRow& row, RayLog& log) const {
        const int per_batch = static_cast<int>(qmc_.size());
        const bool specular = context_.specular.any();
        auto& sums = weights_.local();
        sums.resize(context_.mesh.patches.size());
        auto& batch = batch_reached_.local();
        double batch_squares = 0; // sum over b and j of p_bj^2
        for (int b = 0; b < batches_; ++b) {
            const double rot[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
            batch.clear();
            for (int r = 0; r < per_batch; ++r) {
                const auto [origin, dir] = ray_of(i, r, rot, poly, cdf, tu, tv);
                auto reach = [&](std::size_t j, double w) {
                    batch.emplace_back(static_cast<std::uint32_t>(j), w);
                };
                if (specular)
                    follow_paths(i, origin, dir, log, reach);
                else
                    trace_diffuse(i, origin, dir, log, reach);
            }
            batch_squares += sum_of_squared_shares(batch, per_batch);
            for (const auto& [j, w] : batch) sums.add(j, w);
        }
        double squares = 0; // sum over j of p_j^2
        sums.drain([&](std::size_t j, double sum) {
            const double f = sum / rays_;
            row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(f));
            squares += f * f;
        });
        const double count = batches_;
        const double variance = (batch_squares - count * squares) / (count * (count - 1));
        log.standard_error = static_cast<float>(std::sqrt(std::max(0.0, variance)));
        return static_cast<std::uint64_t>(rays_);
    }

    // One ray of a mesh without mirrors or glass: reach(j, 1) when it meets another patch's
    // front.
    template <class Reach>
    void trace_diffuse(std::size_t i, const Vec3& origin, const Vec3& dir, RayLog& log,
                       Reach&& reach) const {
        const auto traced = context_.scene.trace(origin, dir);
        const bool self = static_cast<std::size_t>(traced.patch) == i;
        log.record(self ? -1 : traced.patch, traced.front, traced.distance);
        if (traced.patch >= 0 && traced.front && !self)
            reach(static_cast<std::size_t>(traced.patch), 1.0);
    }

    // sum_j (w_j / rays)^2 over one batch's reached (patch, weight) pairs (sorted here).
    static double sum_of_squared_shares(std::vector<std::pair<std::uint32_t, double>>& reached,
                                        int rays) {
        std::sort(reached.begin(), reached.end());
        double out = 0;
        for (std::size_t k = 0; k < reached.size();) {
            double share = 0;
            const auto j = reached[k].first;
            for (; k < reached.size() && reached[k].first == j; ++k) share += reached[k].second;
            share /= rays;
            out += share * share;
        }
        return out;
    }

    const FormFactorContext& context_;
    int rays_;
    int batches_; // 0: one stratified set of rays_, no error
    std::vector<std::array<double, 4>> qmc_;
    // One batch's reached (patch, weight) pairs, per thread.
    mutable tbb::enumerable_thread_specific<std::vector<std::pair<std::uint32_t, double>>>
        batch_reached_;
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
        std::vector<std::pair<std::string, std::string>> fields{
            {"rays", std::to_string(options.rays)}};
        if (options.error_batches > 0)
            fields.emplace_back("error_batches", std::to_string(options.error_batches));
        return fields;
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
        // In batches (--error), each thread also holds a batch's reached patches, and
        // sums weights in doubles.
        const bool batched = options.error_batches > 0;
        const std::uint64_t per_batch = batched ? rays / options.error_batches : 0;
        return rays * sizeof(std::array<double, 4>) +
               std::uint64_t(threads) *
                   (mesh.patches.size() * (batched ? 8 : per_patch) + mesh.patches.size() / 8 + 1 +
                    per_batch * sizeof(std::pair<std::uint32_t, double>));
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
