// Direct light of a final gather: the lights a point's cut of the light tree holds, each by
// its exact form factor (a single light) or as one (a far group), times its visible fraction.
#include "formfactor/sampling.hpp"
#include "gather/light_tree.hpp"
#include "gather/virtual_sources.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/patch_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rad {
using gather::brightness;

namespace {
// The visible fraction of a light from shadow rays to points on it: each ray weighted by the
// form-factor kernel cos cos / r^2, so a half-hidden light counts by what it gives (the
// plain share of rays when none has weight).
struct KernelTally {
    double weight_sum = 0;
    Rgb visible_sum{0, 0, 0}, plain_visible{0, 0, 0};
    // One ray from `point` (facing `normal`) to `q` on a light facing `light_normal`;
    // `visible` casts it (not when q is the point itself) and says what of each channel
    // arrives (1 unblocked, 0 blocked, a pane's transmission through glass).
    template <class Visible>
    void add(const Vec3& point, const Vec3& normal, const Vec3& q, const Vec3& light_normal,
             Visible visible) {
        const Vec3 d = q - point;
        const double r2 = dot(d, d);
        if (!(r2 > 0)) return;
        const double w =
            std::max(0.0, dot(d, normal)) * std::max(0.0, -dot(d, light_normal)) / (r2 * r2);
        const Rgb seen = visible(q);
        weight_sum += w;
        for (int c = 0; c < 3; ++c) {
            visible_sum[c] += w * seen[c];
            plain_visible[c] += seen[c];
        }
    }
    Rgb fraction(int rays) const {
        Rgb out;
        for (int c = 0; c < 3; ++c)
            out[c] = weight_sum > 0 ? visible_sum[c] / weight_sum : plain_visible[c] / rays;
        return out;
    }
};

// A stratified number in [0, 1) for sample s of `count`, turned by `offset`.
double stratum(int s, int count, double offset) {
    return ff::wrap((s + 0.5) / count + offset);
}
} // namespace

// The exact form factor from the point to the part of `patch` above the point's plane (0
// when the point is behind the patch); `clipped` receives that part.
double Gatherer::form_factor_to(const Vec3& point, const Vec3& normal, std::size_t patch,
                                std::vector<Vec3>& clipped) const {
    const auto& p = mesh_.patches[patch];
    clipped.clear();
    if (dot(point - p.centroid, p.normal) <= 0) return 0; // behind it
    // A patch in the point's own plane, facing its way (the surface the point lies on, its
    // corners off that plane by rounding): a plane sees nothing of itself. Left in, a point
    // over the patch had its form factor as 1, or 0.5 on an edge.
    if (dot(normal, p.normal) > 0.999) {
        double off = 0;
        for (const auto v : mesh_.corners(p))
            off = std::max(off, std::abs(dot(mesh_.vertices[v] - point, normal)));
        if (off <= 1e-6 * std::sqrt(p.area)) return 0;
    }
    // Clipping a polygon that is not convex may leave pairs of opposite edges along the
    // plane: they cancel in the contour integral.
    std::array<Vec3, 4> few;
    std::vector<Vec3> many;
    ff::clip_to_front(patch_points(mesh_, patch, few, many), point, normal, clipped);
    if (clipped.size() < 3) return 0;
    const double f = point_to_polygon_form_factor(point, normal, clipped);
    return f > 0 ? f : 0;
}

// The part of `clipped` (of `patch`) the point sees: shadow rays to stratified points,
// weighted by the form-factor kernel, so a half-hidden patch counts by what it contributes.
Rgb Gatherer::visible_fraction(const Vec3& point, const Vec3& normal, std::size_t patch,
                               const std::vector<Vec3>& clipped, int rays, Rng& rng) const {
    if (rays <= 0) return {1, 1, 1};
    const auto& p = mesh_.patches[patch];
    // A polygon clipped need not be star-shaped, so its fan could reach outside it: the
    // points are drawn on the whole polygon, where those behind the point weigh nothing.
    const auto whole = p.is_polygon() ? patch_points(mesh_, patch) : std::vector<Vec3>();
    const std::span<const Vec3> region = p.is_polygon() ? std::span<const Vec3>(whole) : clipped;
    const auto cdf = ff::fan_cdf(region);
    const double offset = rng.uniform();
    KernelTally tally;
    for (int s = 0; s < rays; ++s) {
        const Vec3 q =
            ff::uniform_point(region, cdf, stratum(s, rays, offset), rng.uniform(), rng.uniform());
        tally.add(point, normal, q, p.normal,
                  [&](const Vec3& at) { return seen_through(point, at); });
    }
    return tally.fraction(rays);
}

// An area-uniform point of the whole patch, `u` (in [0, 1)) choosing where along its fan.
Vec3 Gatherer::point_on_light(std::size_t patch, double u, Rng& rng) const {
    std::array<Vec3, 4> few;
    std::vector<Vec3> many;
    const auto polygon = patch_points(mesh_, patch, few, many);
    std::array<double, 2> few_cdf{quad_first_share_[patch], 1}; // a quad's or a triangle's
    std::vector<double> many_cdf;
    const auto cdf = polygon.size() <= 4
                         ? std::span<const double>(few_cdf.data(), polygon.size() - 2)
                         : ff::fan_cdf(polygon, few_cdf, many_cdf);
    return ff::uniform_point(polygon, cdf, u, rng.uniform(), rng.uniform());
}

// A cluster's visible fraction: shadow rays to its lights, each chosen in proportion to its
// power and a point on it uniformly, so the kernel-weighted ratio weighs them as they shine.
Rgb Gatherer::cluster_visible_fraction(const Vec3& point, const Vec3& normal, std::uint32_t node,
                                       int rays, Rng& rng) const {
    const double offset = rng.uniform();
    KernelTally tally;
    for (int s = 0; s < rays; ++s) {
        double along = 0; // the stratum's rest, so the points on a light are stratified too
        const auto& light = lights_->pick(node, stratum(s, rays, offset), &along);
        const Vec3 q = point_on_light(light.patch, along, rng);
        tally.add(point, normal, q, mesh_.patches[light.patch].normal,
                  [&](const Vec3& at) { return seen_through(point, at); });
    }
    return tally.fraction(rays);
}

// The visible fraction of lights too faint for a shadow ray each, together: each ray goes to
// one of them chosen by its weight, and the share of rays that arrive stands for them all.
Rgb Gatherer::pooled_visible_fraction(const Vec3& point, std::span<const Seen* const> pooled,
                                      double weight, int rays, Rng& rng) const {
    const double offset = rng.uniform();
    Rgb visible{0, 0, 0};
    std::size_t at = 0;
    double below = 0; // the weight of pooled[0, at)
    for (int s = 0; s < rays; ++s) {
        const double target = stratum(s, rays, offset) * weight;
        // Strata ascend but wrap once: start over when the target falls behind.
        if (target < below) at = 0, below = 0;
        while (at + 1 < pooled.size() && below + pooled[at]->weight <= target)
            below += pooled[at++]->weight;
        const Seen& seen = *pooled[at];
        Vec3 q;
        if (seen.cluster) {
            double along = 0;
            const auto& light = lights_->pick(seen.id, rng.uniform(), &along);
            q = point_on_light(light.patch, along, rng);
        } else {
            std::array<double, 2> few_cdf;
            std::vector<double> many_cdf;
            const auto cdf = ff::fan_cdf(seen.clipped, few_cdf, many_cdf);
            q = ff::uniform_point(seen.clipped, cdf, rng.uniform(), rng.uniform(), rng.uniform());
        }
        const Rgb arrives = seen_through(point, q);
        for (int c = 0; c < 3; ++c) visible[c] += arrives[c];
    }
    for (int c = 0; c < 3; ++c) visible[c] /= rays;
    return visible;
}

// Shadow rays shared by what each seen light gives: one with a share of at least half a ray
// gets its own (rounded), the rest share theirs as one pool.
void Gatherer::share_shadow_rays(std::span<Seen> seen, double total, int budget,
                                 ShadowShares& out) const {
    out.own.clear();
    out.pooled.clear();
    out.pooled_weight = 0;
    out.pooled_sum = {0, 0, 0};
    out.pooled_rays = 0;
    if (!(total > 0)) return;
    for (const auto& s : seen) {
        const double share = budget * s.weight / total;
        if (budget > 0 && share < 0.5) {
            out.pooled.push_back(&s);
            out.pooled_weight += s.weight;
            for (int k = 0; k < 3; ++k) out.pooled_sum[k] += s.irradiance[k];
            continue;
        }
        out.own.push_back({&s, budget <= 0 ? 0 : static_cast<int>(std::lround(share))});
    }
    if (!out.pooled.empty())
        out.pooled_rays =
            std::max(1, static_cast<int>(std::lround(budget * out.pooled_weight / total)));
}

Rgb Gatherer::shadowed(const Vec3& point, const Vec3& normal, const ShadowShares& shares,
                       Rng& rng) const {
    Rgb sum{0, 0, 0};
    for (const auto& [s, rays] : shares.own) {
        const Rgb visible = rays == 0 ? Rgb{1, 1, 1}
                            : s->cluster
                                ? cluster_visible_fraction(point, normal, s->id, rays, rng)
                                : visible_fraction(point, normal, s->id, s->clipped, rays, rng);
        for (int k = 0; k < 3; ++k) sum[k] += s->irradiance[k] * visible[k];
    }
    if (!shares.pooled.empty()) {
        const Rgb visible = pooled_visible_fraction(point, shares.pooled, shares.pooled_weight,
                                                    shares.pooled_rays, rng);
        for (int k = 0; k < 3; ++k) sum[k] += shares.pooled_sum[k] * visible[k];
    }
    return sum;
}

namespace {
// The point's cut of the light tree.
void find_cut(const gather::LightTree& lights, const GatherOptions& o, const Vec3& point,
              const Vec3& normal, gather::LightTree::Cut& cut) {
    // Exact: every light on its own too, no cluster's approximation.
    // (cluster_ratio 0: every light on its own, none taken as one.)
    const double tolerance = o.exact || o.cluster_tolerance <= 0 || o.cluster_ratio <= 0
                                 ? 0
                                 : o.cluster_tolerance * lights.rough_irradiance(point, normal);
    lights.cut(point, normal, o.exact ? 0 : o.cluster_ratio, cut, tolerance);
}
} // namespace

// The point's cut of the light tree (or the one `kept`): single lights by their exact form
// factors, groups as one, unshadowed (the buffers of `out` reused).
void Gatherer::seen_lights(const Vec3& point, const Vec3& normal, SeenLights& out,
                           KeptCut* kept) const {
    out.total = 0;
    out.count = 0;
    if (lights_->empty()) return;
    thread_local gather::LightTree::Cut cut;
    if (kept && kept->held) {
        cut.lights = kept->lights;
        cut.clusters.clear();
        for (const auto node : kept->clusters)
            cut.clusters.push_back({node, lights_->cluster_irradiance(node, point, normal)});
    } else {
        find_cut(*lights_, options_, point, normal, cut);
        if (kept) {
            kept->lights = cut.lights;
            kept->clusters.clear();
            for (const auto& c : cut.clusters) kept->clusters.push_back(c.node);
            kept->held = true;
        }
    }
    auto& seen = out.lights;
    for (const auto i : cut.lights) {
        if (out.count == seen.size()) seen.emplace_back();
        Seen& s = seen[out.count];
        if (value_light(i, point, normal, s) <= 0) continue;
        out.total += s.weight;
        ++out.count;
    }
    for (const auto& c : cut.clusters) {
        if (!(brightness(c.irradiance) > 0)) continue;
        if (out.count == seen.size()) seen.emplace_back();
        Seen& s = seen[out.count++];
        s.cluster = true;
        s.id = c.node;
        s.order = lights_->first_of(c.node);
        s.irradiance = c.irradiance;
        s.weight = brightness(c.irradiance);
        out.total += s.weight;
    }
}

double Gatherer::value_light(std::uint32_t light, const Vec3& point, const Vec3& normal,
                             Seen& s) const {
    const auto& l = lights_->lights()[light];
    const double f = form_factor_to(point, normal, l.patch, s.clipped);
    s.cluster = false;
    s.id = l.patch;
    s.order = light;
    for (int k = 0; k < 3; ++k) s.irradiance[k] = l.radiosity[k] * f;
    s.weight = brightness(s.irradiance);
    return f;
}

namespace {
// Where `s` falls in a cut's order: its single lights, then its groups, each in the tree's.
bool comes_before(const Gatherer::Seen& s, const Gatherer::Seen& t) {
    return s.cluster != t.cluster ? !s.cluster : s.order < t.order;
}

// Whether a light giving `from` and `to` (its weights) at two points may be blended between
// them: the error of a straight line through a light that falls as a power of distance is
// about (to - from)^2 / 4 x its light, kept under 1e-5 of the whole (`total`) for each.
bool blends(double from, double to, double total) {
    const double change = to - from;
    return change * change <= 4e-5 * total * std::max(from, to);
}
} // namespace

void Gatherer::seen_between(const SeenLights& a, const SeenLights& b, double share,
                            const Vec3& point, const Vec3& normal, SeenLights& out) const {
    if (out.lights.size() < a.count) out.lights.resize(a.count);
    out.count = 0;
    out.total = 0;
    std::size_t j = 0; // b's entries, walked beside a's in the cut's order
    for (std::size_t k = 0; k < a.count; ++k) {
        const Seen& from = a.lights[k];
        while (j < b.count && comes_before(b.lights[j], from)) ++j;
        const bool in_b = j < b.count && b.lights[j].cluster == from.cluster &&
                          b.lights[j].id == from.id &&
                          blends(from.weight, b.lights[j].weight, a.total);
        Seen& s = out.lights[out.count];
        if (!from.cluster && !in_b) {
            if (value_light(from.order, point, normal, s) <= 0) continue;
        } else {
            s.cluster = from.cluster;
            s.id = from.id;
            s.order = from.order;
            if (in_b) {
                const Seen& to = b.lights[j];
                for (int c = 0; c < 3; ++c)
                    s.irradiance[c] =
                        from.irradiance[c] + share * (to.irradiance[c] - from.irradiance[c]);
                s.clipped = from.clipped;
            } else {
                s.irradiance = lights_->cluster_irradiance(from.id, point, normal);
            }
            s.weight = brightness(s.irradiance);
        }
        if (!(s.weight > 0)) continue;
        out.total += s.weight;
        ++out.count;
    }
}

// One batch's direct light: the seen lights with shadow rays shared among them by what each
// gives, and the emitters seen in planar mirrors.
Rgb Gatherer::direct_batch(const Vec3& point, const Vec3& normal, const ShadowShares& shares,
                           int shadow_rays, Rng& rng) const {
    Rgb out = shadowed(point, normal, shares, rng);
    // (Nothing, and no random number drawn, without mirrors.)
    const Rgb imaged = virtual_->irradiance(point, normal, *scene_, shadow_rays, rng);
    for (int k = 0; k < 3; ++k) out[k] += imaged[k];
    return out;
}

// What of each channel travels from `from` to `to`: 1 unblocked, 0 blocked, and through thin
// panes of glass their transmission at the angle met (the light of lamps behind glazing).
Rgb Gatherer::seen_through(const Vec3& from, const Vec3& to) const {
    return straight_transmission(*scene_, *specular_, from, to, options_.specular_depth);
}

} // namespace rad
