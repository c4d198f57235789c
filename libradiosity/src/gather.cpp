// Final gather at arbitrary points: direct light sampled on the emitters, indirect light from
// cosine-weighted rays (or the exact point-to-polygon sum).
#include "radiosity/gather.hpp"

#include "formfactor/sampling.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/random.hpp"

#include <algorithm>
#include <cmath>

namespace rad {

namespace {
bool emits(const Rgb& e) {
    return e[0] > 0 || e[1] > 0 || e[2] > 0;
}

std::vector<Vec3> corners_of(const radfmt::MeshData& mesh, std::size_t patch) {
    const auto& p = mesh.patches[patch];
    std::vector<Vec3> out;
    for (int k = 0; k < p.corner_count(); ++k) out.push_back(mesh.vertices[p.corners[k]]);
    return out;
}

// Rays from a point are stratified: a (0,2)-net rotated per point by seeded offsets.
Vec3 stratified_direction(const Vec3& n, const Vec3& tu, const Vec3& tv, int r, int rays,
                          const double rotation[2]) {
    const double u = ff::wrap((r + 0.5) / rays + rotation[0]);
    const double v = ff::wrap(ff::radical_inverse(static_cast<std::uint64_t>(r), 2) + rotation[1]);
    return cosine_direction(n, tu, tv, u, v);
}

Rgb interpolate(const std::array<Rgb, 4>& c, int corners, double u, double v) {
    Rgb out;
    for (int k = 0; k < 3; ++k)
        out[k] = corners == 3 ? (1 - u - v) * c[0][k] + u * c[1][k] + v * c[2][k]
                              : (1 - u) * (1 - v) * c[0][k] + u * (1 - v) * c[1][k] +
                                    u * v * c[2][k] + (1 - u) * v * c[3][k];
    return out;
}
} // namespace

Gatherer::Gatherer(const radfmt::MeshData& mesh, std::span<const Rgb> radiosity,
                   GatherOptions options)
    : mesh_(mesh), options_(options), scene_(std::make_unique<RayScene>(mesh)) {
    const std::size_t n = mesh.patches.size();
    emission_.resize(n);
    reflected_flat_.resize(n);
    std::vector<Rgb> total(radiosity.begin(), radiosity.end());
    for (std::size_t i = 0; i < n; ++i) {
        emission_[i] = mesh.materials[mesh.patches[i].material].emission;
        for (int k = 0; k < 3; ++k)
            reflected_flat_[i][k] = std::max(0.0, radiosity[i][k] - emission_[i][k]);
        if (emits(emission_[i])) emitters_.push_back(static_cast<std::uint32_t>(i));
    }
    total_corners_ = corner_colours(mesh, total, options.smoothing, options.crease_deg);
    reflected_corners_ =
        corner_colours(mesh, reflected_flat_, options.smoothing, options.crease_deg);
}

Gatherer::~Gatherer() = default;

Rgb Gatherer::radiosity_at(std::size_t patch, double u, double v) const {
    return interpolate(total_corners_[patch], mesh_.patches[patch].corner_count(), u, v);
}

Rgb Gatherer::reflected_at(std::size_t patch, double u, double v) const {
    return interpolate(reflected_corners_[patch], mesh_.patches[patch].corner_count(), u, v);
}

// The exact form factor from the point to the part of `patch` above the point's plane,
// times the part of it the point sees (shadow rays to stratified points, weighted by the
// form-factor kernel so that a half-hidden emitter counts by what it contributes).
Rgb Gatherer::visible_sum(const Vec3& point, const Vec3& normal, std::size_t patch,
                          Rng& rng) const {
    const auto& p = mesh_.patches[patch];
    if (dot(point - p.centroid, p.normal) <= 0) return {0, 0, 0}; // behind it
    const auto poly = corners_of(mesh_, patch);
    const auto clipped = ff::clip_to_front(poly, point, normal);
    if (clipped.size() < 3) return {0, 0, 0};
    const double form_factor = point_to_polygon_form_factor(point, normal, clipped);
    if (!(form_factor > 0)) return {0, 0, 0};
    double seen = 1;
    if (options_.shadow_rays > 0) {
        const auto cdf = ff::fan_cdf(clipped);
        const double offset = rng.uniform();
        double weight_sum = 0, visible_sum = 0, plain_visible = 0;
        for (int s = 0; s < options_.shadow_rays; ++s) {
            const double u0 = ff::wrap((s + 0.5) / options_.shadow_rays + offset);
            const Vec3 q = ff::uniform_point(clipped, cdf, u0, rng.uniform(), rng.uniform());
            const Vec3 d = q - point;
            const double r2 = dot(d, d);
            if (!(r2 > 0)) continue;
            const double w =
                std::max(0.0, dot(d, normal)) * std::max(0.0, -dot(d, p.normal)) / (r2 * r2);
            const bool visible = scene_->visible(point, q);
            weight_sum += w;
            visible_sum += visible ? w : 0;
            plain_visible += visible ? 1 : 0;
        }
        seen = weight_sum > 0 ? visible_sum / weight_sum : plain_visible / options_.shadow_rays;
    }
    const double f = form_factor * seen;
    return {f, f, f};
}

Rgb Gatherer::direct(const Vec3& point, const Vec3& normal, std::uint64_t index) const {
    Rng rng(options_.seed ^ 0xD1EC7ull, index);
    Rgb sum{0, 0, 0};
    for (const auto j : emitters_) {
        const auto f = visible_sum(point, normal, j, rng);
        for (int k = 0; k < 3; ++k) sum[k] += emission_[j][k] * f[k];
    }
    return sum;
}

Rgb Gatherer::exact_indirect(const Vec3& point, const Vec3& normal, std::uint64_t index) const {
    Rng rng(options_.seed ^ 0xE8AC7ull, index);
    Rgb sum{0, 0, 0};
    for (std::size_t j = 0; j < mesh_.patches.size(); ++j) {
        const auto& b = reflected_flat_[j];
        if (!(b[0] > 0 || b[1] > 0 || b[2] > 0)) continue;
        const auto f = visible_sum(point, normal, j, rng);
        for (int k = 0; k < 3; ++k) sum[k] += b[k] * f[k];
    }
    return sum;
}

Irradiance Gatherer::gather(const Vec3& point, const Vec3& normal, std::uint64_t index) const {
    Irradiance out;
    out.direct = direct(point, normal, index);
    // Rays from the point: the indirect estimate, and in any case the evidence of where the
    // point is (a point inside an object sees the backs of its faces).
    Rng rng(options_.seed, index);
    const double rotation[2] = {rng.uniform(), rng.uniform()};
    const Vec3 tu = orthogonal(normal), tv = cross(normal, tu);
    const int rays = options_.exact || options_.rays <= 0 ? 64 : options_.rays;
    Rgb sum{0, 0, 0};
    int backs = 0, hits = 0;
    for (int r = 0; r < rays; ++r) {
        const auto hit =
            scene_->trace(point, stratified_direction(normal, tu, tv, r, rays, rotation));
        if (hit.patch < 0) continue;
        ++hits;
        if (!hit.front) {
            ++backs;
            continue;
        }
        const auto b = reflected_at(static_cast<std::size_t>(hit.patch), hit.u, hit.v);
        for (int k = 0; k < 3; ++k) sum[k] += b[k];
    }
    out.hit_fraction = double(hits) / rays;
    out.back_fraction = hits ? double(backs) / hits : 0;
    if (options_.exact)
        out.indirect = exact_indirect(point, normal, index);
    else if (options_.rays > 0)
        for (int k = 0; k < 3; ++k) out.indirect[k] = sum[k] / rays;
    return out;
}

} // namespace rad
