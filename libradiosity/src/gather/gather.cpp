// Final gather at arbitrary points: direct light sampled on the emitters, indirect light from
// cosine-weighted rays (or the exact point-to-polygon sum).
#include "radiosity/gather.hpp"

#include "formfactor/sampling.hpp"
#include "gather/light_tree.hpp"
#include "gather/virtual_sources.hpp"
#include "radiosity/batch_error.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/irradiance_gradients.hpp"
#include "radiosity/patch_geometry.hpp"
#include "radiosity/random.hpp"

#include <algorithm>
#include <cmath>

namespace rad {
using gather::brightness;

namespace {
bool emits(const Rgb& e) {
    return e[0] > 0 || e[1] > 0 || e[2] > 0;
}

// Rays from a point are stratified: a (0,2)-net rotated per point by seeded offsets.
Vec3 stratified_direction(const Vec3& n, const Vec3& tu, const Vec3& tv, int r, int rays,
                          const double rotation[2]) {
    const double u = ff::wrap((r + 0.5) / rays + rotation[0]);
    const double v = ff::wrap(ff::radical_inverse(static_cast<std::uint64_t>(r), 2) + rotation[1]);
    return cosine_direction(n, tu, tv, u, v);
}

// The corner values at a hit.
Rgb interpolate(const radfmt::MeshData& mesh, const CornerColours& c, const RayScene::Hit& hit) {
    return interpolate_corners(mesh, c, hit.patch, hit.u, hit.v, hit.piece);
}
} // namespace

Gatherer::Gatherer(const radfmt::MeshData& mesh, std::span<const Rgb> radiosity,
                   GatherOptions options)
    : mesh_(mesh), options_(options), scene_(std::make_unique<RayScene>(mesh)),
      specular_(std::make_unique<SpecularSurfaces>(mesh)) {
    if (options_.exact && specular_->any())
        throw InputError("--exact sums the light of every patch seen directly and does not "
                         "follow mirrors and glass, which this mesh has: leave --exact out (rays "
                         "go on through them)");
    const std::size_t n = mesh.patches.size();
    emission_.resize(n);
    reflected_flat_.resize(n);
    std::vector<Rgb> total(radiosity.begin(), radiosity.end());
    for (std::size_t i = 0; i < n; ++i) {
        emission_[i] = mesh.materials[mesh.patches[i].material].emission;
        for (int k = 0; k < 3; ++k)
            reflected_flat_[i][k] = std::max(0.0, radiosity[i][k] - emission_[i][k]);
    }
    find_bright_patches();
    build_light_tree();
    // Shadow rays pick points on lights by their fan's areas: a quad's split once here.
    quad_first_share_.assign(n, 1);
    for (std::size_t i = 0; i < n; ++i)
        if (mesh.corners(i).size() == 4)
            quad_first_share_[i] = ff::fan_cdf(patch_points(mesh, i))[0];
    virtual_ = std::make_unique<gather::VirtualSources>(mesh, *specular_, emission_);
    total_corners_ = corner_colours(mesh, total, options.smoothing, options.crease_deg);
    // Each patch keeps its solved mean under the smoothing (keep_patch_means): a point beside
    // a dark patch among brighter ones sees it at a wide angle. Flat values have it already.
    reflected_corners_ =
        corner_colours(mesh, reflected_flat_, options.smoothing, options.crease_deg);
    if (options.smoothing != Smoothing::Flat)
        keep_patch_means(mesh, reflected_flat_, reflected_corners_);
    // Normals smoothed over neighbours of the same material within the crease angle (never
    // round a box's edges), or not at all when the values are flat.
    std::vector<Rgb> normals;
    for (const auto& p : mesh.patches) normals.push_back({p.normal[0], p.normal[1], p.normal[2]});
    corner_normals_ = corner_colours(
        mesh, normals, options.smoothing == Smoothing::Flat ? Smoothing::Flat : Smoothing::Crease,
        options.crease_deg);
}

// Patches whose reflected radiosity stands far above the scene's mean: a few rays landing on
// one would dominate a point's estimate, so they are lights instead.
void Gatherer::find_bright_patches() {
    const std::size_t n = mesh_.patches.size();
    bright_.assign(n, 0);
    if (options_.exact || options_.rays <= 0 || options_.bright_factor <= 0) return;
    double area = 0, weighted = 0;
    for (std::size_t i = 0; i < n; ++i) {
        area += mesh_.patches[i].area;
        weighted += mesh_.patches[i].area * brightness(reflected_flat_[i]);
    }
    if (!(area > 0 && weighted > 0)) return;
    const double limit = options_.bright_factor * weighted / area;
    for (std::size_t i = 0; i < n; ++i) bright_[i] = brightness(reflected_flat_[i]) > limit;
}

Gatherer::~Gatherer() = default;

const PlanarMirrors& Gatherer::mirrors() const {
    return virtual_->mirrors();
}

std::size_t Gatherer::bright_patches() const {
    return static_cast<std::size_t>(std::count(bright_.begin(), bright_.end(), 1));
}

// The lights: every emitter with its E, and every bright patch with what it reflects.
void Gatherer::build_light_tree() {
    std::vector<gather::Light> lights;
    for (std::size_t i = 0; i < mesh_.patches.size(); ++i) {
        Rgb sent = emission_[i];
        if (bright_[i])
            for (int k = 0; k < 3; ++k) sent[k] += reflected_flat_[i][k];
        if (emits(sent)) lights.push_back({static_cast<std::uint32_t>(i), sent});
    }
    lights_ = std::make_unique<gather::LightTree>(mesh_, std::move(lights));
}

Vec3 Gatherer::shading_normal(const RayScene::Hit& hit) const {
    const auto c = interpolate(mesh_, corner_normals_, hit);
    const Vec3 n{c[0], c[1], c[2]};
    const double len = length(n);
    return len > 0 ? n * (1 / len) : mesh_.patches[static_cast<std::size_t>(hit.patch)].normal;
}

Rgb Gatherer::radiosity_at(const RayScene::Hit& hit) const {
    return interpolate(mesh_, total_corners_, hit);
}

Rgb Gatherer::reflected_at(const RayScene::Hit& hit) const {
    return interpolate(mesh_, reflected_corners_, hit);
}

Rgb Gatherer::exact_indirect(const Vec3& point, const Vec3& normal, std::uint64_t index) const {
    Rng rng(options_.seed ^ 0xE8AC7ull, index);
    Rgb sum{0, 0, 0};
    std::vector<Vec3> clipped;
    for (std::size_t j = 0; j < mesh_.patches.size(); ++j) {
        const auto& b = reflected_flat_[j];
        if (!(b[0] > 0 || b[1] > 0 || b[2] > 0)) continue;
        const double f = form_factor_to(point, normal, j, clipped);
        if (f <= 0) continue;
        const Rgb seen = visible_fraction(point, normal, j, clipped, options_.shadow_rays, rng);
        for (int k = 0; k < 3; ++k) sum[k] += b[k] * f * seen[k];
    }
    return sum;
}

Irradiance Gatherer::gather(const Vec3& point, const Vec3& normal, std::uint64_t index,
                            const Rgb& known) const {
    return gather(point, normal, normal, index, known);
}

// What the rays from a point met: the evidence of where the point is (a point inside an
// object sees the backs of its faces).
struct Gatherer::Evidence {
    long rays = 0, hits = 0, backs = 0;
    double inverse_distance = 0; // the sum of 1 / distance over the hits (not through glass)
};

namespace {
// How a point's rays are cast: per batch, and how many batches at least and at most, of the
// direct light's shadow rays and of the indirect rays (each its own set of batches).
struct BatchPlan {
    int rays = 0, shadow_rays = 0, first = 1, most_direct = 1, most_indirect = 1;
};

BatchPlan plan_batches(const GatherOptions& o) {
    BatchPlan plan;
    const int batches = o.exact ? 1 : std::max(1, o.batches);
    // Without indirect rays (and --exact) the rays still look for where the point is.
    const int rays = o.exact || o.rays <= 0 ? 64 : o.rays;
    // At least 8 rays a batch where there are 16 or more: a batch of very few rays takes few
    // distinct values, and its batches can agree exactly where the value is not exact.
    plan.first = std::min(batches, std::max(std::min(2, rays), rays / 8));
    plan.rays = std::max(1, rays / plan.first);
    plan.shadow_rays = o.shadow_rays <= 0 ? 0 : std::max(1, o.shadow_rays / plan.first);
    plan.most_direct = plan.most_indirect = plan.first;
    if (o.accuracy > 0 && plan.first > 1) {
        const auto most = [&](int per_batch) {
            return static_cast<int>(
                std::clamp<long>(long(o.max_rays) / std::max(1, per_batch), plan.first, 1 << 24));
        };
        if (o.rays > 0 && !o.exact) plan.most_indirect = most(plan.rays);
        if (plan.shadow_rays > 0) plan.most_direct = most(plan.shadow_rays);
    }
    return plan;
}

// The batches of each kind the accuracy asks for: rays shared between the direct light's
// shadow rays and the indirect rays as the square roots of their variances per ray (which
// reaches a variance at least cost), rounded up to whole batches, never fewer than cast.
void more_batches(const BatchError& direct, const BatchError& indirect, const BatchPlan& plan,
                  double wanted, int& direct_target, int& indirect_target) {
    const double vd = direct.luminous_error(), vi = indirect.luminous_error();
    // Variance of one ray's worth: the mean's variance x the rays it took.
    const double per_d = vd * vd * direct.count() * std::max(1, plan.shadow_rays);
    const double per_i = vi * vi * indirect.count() * plan.rays;
    const double sd = std::sqrt(std::isfinite(per_d) ? per_d : 0);
    const double si = std::sqrt(std::isfinite(per_i) ? per_i : 0);
    const double scale = (sd + si) / (wanted * wanted);
    const auto target = [&](double sigma, int per_batch, int now, int most) {
        const double batches = std::ceil(sigma * scale / std::max(1, per_batch));
        return static_cast<int>(std::clamp<double>(batches, now, most));
    };
    direct_target = target(sd, plan.shadow_rays, direct.count(), plan.most_direct);
    indirect_target = target(si, plan.rays, indirect.count(), plan.most_indirect);
}

// The standard error of a sum of two independent estimates.
double combined(double a, double b) {
    return std::sqrt(a * a + b * b);
}
} // namespace

// The direct light's batches and the indirect light's, each from its own stream, until the
// error is below the accuracy asked for (or the budget is spent). The two sets are
// independent, so the error of their sum is the root of the sum of their squared errors.
Irradiance Gatherer::gather(const Vec3& point, const Vec3& normal, const Vec3& surface,
                            std::uint64_t index, const Rgb& known) const {
    const BatchPlan plan = plan_batches(options_);
    thread_local SeenLights seen;
    seen_lights(point, normal, seen);
    thread_local ShadowShares shares; // the same for every batch: shared once
    share_shadow_rays(seen.seen(), seen.total, plan.shadow_rays, shares);
    BatchError direct, indirect;
    Evidence evidence;
    int direct_target = plan.first, indirect_target = plan.first;
    for (;;) {
        while (direct.count() < direct_target) {
            Rng rng = batch_stream(options_.seed ^ 0xD1EC7ull, index, direct.count());
            direct.add(direct_batch(point, normal, shares, plan.shadow_rays, rng));
        }
        while (indirect.count() < indirect_target) {
            Rng rng = batch_stream(options_.seed, index, indirect.count());
            indirect.add(indirect_batch(point, normal, surface, plan.rays, rng, evidence));
        }
        // The known light counts in the target: the error is relative to the whole value.
        const double mean = direct.luminous_mean() + indirect.luminous_mean() + luminous(known);
        const double wanted = options_.accuracy * std::abs(mean);
        const double error = combined(direct.luminous_error(), indirect.luminous_error());
        if (options_.accuracy <= 0 || !(error > wanted) || !(wanted > 0)) break;
        const int had_direct = direct_target, had_indirect = indirect_target;
        more_batches(direct, indirect, plan, wanted, direct_target, indirect_target);
        if (direct_target == had_direct && indirect_target == had_indirect) break; // the budget
    }
    Irradiance out;
    out.direct = direct.mean();
    out.indirect = indirect.mean();
    if (options_.exact) out.indirect = exact_indirect(point, normal, index);
    const Rgb ed = direct.standard_error(), ei = indirect.standard_error();
    for (int k = 0; k < 3; ++k) out.error[k] = combined(ed[k], ei[k]);
    out.luminous_error = combined(direct.luminous_error(), indirect.luminous_error());
    out.rays_cast = options_.rays > 0 && !options_.exact ? indirect.count() * plan.rays : 0;
    out.at_budget =
        options_.accuracy > 0 &&
        out.luminous_error > options_.accuracy * std::abs(luminous(out.total()) + luminous(known));
    out.hit_fraction = evidence.rays ? double(evidence.hits) / evidence.rays : 0;
    out.back_fraction = evidence.hits ? double(evidence.backs) / evidence.hits : 0;
    return out;
}

// No error bar is asked of it: one set of all the shadow rays (better stratified, and the
// per-batch work once). What a light gives unshadowed changes across a pixel's footprint by
// far less than the shadow rays' noise: its value at their centre stands for each.
void Gatherer::direct_light(const Vec3& centre, const Vec3& facing,
                            std::span<const DirectSample> samples, std::span<Rgb> out,
                            KeptCut* kept) const {
    thread_local SeenLights seen;
    seen_lights(centre, facing, seen, kept);
    direct_light(seen, samples, out);
}

void Gatherer::direct_light(SeenLights& seen, std::span<const DirectSample> samples,
                            std::span<Rgb> out) const {
    thread_local ShadowShares shares; // the same for every sample: shared once
    share_shadow_rays(seen.seen(), seen.total, options_.shadow_rays, shares);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        Rng rng = batch_stream(options_.seed ^ 0xD1EC7ull, samples[k].index, 0);
        out[k] =
            direct_batch(samples[k].point, samples[k].normal, shares, options_.shadow_rays, rng);
    }
}

// One ray a cell of hemisphere_grid(rays), each jittered from the record's own stream; what
// each met feeds the gradients.
Gatherer::IndirectSample Gatherer::indirect_sample(const Vec3& point, const Vec3& normal,
                                                   const Vec3& surface, int rays,
                                                   std::uint64_t index) const {
    if (specular_->any())
        throw InternalError("an irradiance cache's record on a mesh with mirrors or glass");
    const auto [m, n] = hemisphere_grid(rays);
    Rng rng = batch_stream(options_.seed ^ 0xCAC4Eull, index, 0);
    const Vec3 tu = orthogonal(normal), tv = cross(normal, tu);
    thread_local std::vector<HemisphereCell> cells;
    cells.assign(std::size_t(m) * n, HemisphereCell{});
    double inverse_distance = 0, nearest = 0;
    long hits = 0;
    for (int j = 0; j < m; ++j)
        for (int k = 0; k < n; ++k) {
            const double u = rng.uniform(), v = rng.uniform();
            const Vec3 d = hemisphere_cell_direction(j, k, m, n, u, v, normal, tu, tv);
            if (dot(d, surface) <= 0) continue; // into the surface under a shading normal
            const auto ray = diffuse_ray(point, d);
            if (!(ray.distance > 0)) continue;
            // Backs and lights give nothing here, yet bound the cell.
            cells[std::size_t(j) * n + k] = {ray.radiance, ray.distance};
            ++hits;
            inverse_distance += 1 / ray.distance;
            nearest = nearest > 0 ? std::min(nearest, ray.distance) : ray.distance;
        }
    const auto g = irradiance_gradients(cells, m, n, tu, tv);
    IndirectSample out;
    out.indirect = g.mean;
    out.translational = g.translational;
    out.rotational = g.rotational;
    out.harmonic_distance = hits > 0 ? double(hits) / inverse_distance : 0;
    out.nearest = nearest;
    return out;
}

// One batch's indirect light (none without indirect rays: --rays 0, --exact, where the rays
// only look for where the point is).
Rgb Gatherer::indirect_batch(const Vec3& point, const Vec3& normal, const Vec3& surface, int rays,
                             Rng& rng, Evidence& evidence) const {
    const Rgb mean = cast_indirect(point, normal, surface, rays, rng, evidence);
    if (options_.exact || options_.rays <= 0) return {0, 0, 0};
    return mean;
}

// Cosine-weighted stratified rays turned by `rng`, each taking the reflected radiosity where it
// lands (through mirrors and glass): their mean; `evidence` counts what they met.
Rgb Gatherer::cast_indirect(const Vec3& point, const Vec3& normal, const Vec3& surface, int rays,
                            Rng& rng, Evidence& evidence) const {
    const double rotation[2] = {rng.uniform(), rng.uniform()};
    const Vec3 tu = orthogonal(normal), tv = cross(normal, tu);
    Rgb sum{0, 0, 0};
    int backs = 0, hits = 0;
    for (int r = 0; r < rays; ++r) {
        const Vec3 d = stratified_direction(normal, tu, tv, r, rays, rotation);
        if (dot(d, surface) <= 0) continue; // into the surface under a shading normal
        if (specular_->any()) {
            const auto b = specular_ray(point, d, hits, backs);
            for (int k = 0; k < 3; ++k) sum[k] += b[k];
            continue;
        }
        const auto ray = diffuse_ray(point, d);
        if (!(ray.distance > 0)) continue;
        ++hits;
        evidence.inverse_distance += 1 / ray.distance;
        backs += ray.back;
        for (int k = 0; k < 3; ++k) sum[k] += ray.radiance[k];
    }
    evidence.rays += rays;
    evidence.hits += hits;
    evidence.backs += backs;
    for (int k = 0; k < 3; ++k) sum[k] /= rays;
    return sum;
}

Gatherer::RayReturn Gatherer::diffuse_ray(const Vec3& point, const Vec3& d) const {
    const auto hit = scene_->trace(point, d);
    RayReturn out;
    if (hit.patch < 0) return out;
    out.distance = std::max(hit.distance, 1e-9);
    out.back = !hit.front;
    if (hit.front && !bright_[static_cast<std::size_t>(hit.patch)])
        out.radiance = reflected_at(hit);
    return out;
}

Rgb Gatherer::specular_ray(const Vec3& point, const Vec3& d, int& hits, int& backs) const {
    Rgb sum{0, 0, 0};
    follow_specular(*scene_, *specular_, point, d, Rgb{{1, 1, 1}}, options_.specular_depth,
                    [&](const PathHit& h) {
                        const auto j = static_cast<std::size_t>(h.hit.patch);
                        if (h.events == 0) {
                            ++hits;
                            // Glass is met from behind as often as from the front.
                            if (!h.hit.front && !specular_->transmits(j)) ++backs;
                            // Emitters and bright patches seen directly are direct()'s.
                            if (!h.hit.front || bright_[j]) return;
                            const auto b = reflected_at(h.hit);
                            for (int k = 0; k < 3; ++k) sum[k] += b[k];
                            return;
                        }
                        if (!h.hit.front) return;
                        // Through thin panes only, the lights are direct()'s, as when seen
                        // with nothing between; once off a planar mirror, the emitters are
                        // (their images); beyond anything else, direct() does not see: all.
                        Rgb b;
                        if (h.straight) {
                            if (bright_[j]) return;
                            b = reflected_at(h.hit);
                        } else if (h.events == 1 &&
                                   virtual_->images(static_cast<std::size_t>(h.from))) {
                            b = reflected_at(h.hit);
                        } else {
                            b = radiosity_at(h.hit);
                        }
                        for (int k = 0; k < 3; ++k) sum[k] += h.weight[k] * b[k];
                    });
    return sum;
}

} // namespace rad
