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
    // Normals smoothed over neighbours of the same material within the crease angle (never
    // round a box's edges), or not at all when the values are flat.
    std::vector<Rgb> normals;
    for (const auto& p : mesh.patches) normals.push_back({p.normal[0], p.normal[1], p.normal[2]});
    corner_normals_ = corner_colours(
        mesh, normals, options.smoothing == Smoothing::Flat ? Smoothing::Flat : Smoothing::Crease,
        options.crease_deg);
}

Vec3 Gatherer::shading_normal(std::size_t patch, double u, double v) const {
    const auto c = interpolate(corner_normals_[patch], mesh_.patches[patch].corner_count(), u, v);
    const Vec3 n{c[0], c[1], c[2]};
    const double len = length(n);
    return len > 0 ? n * (1 / len) : mesh_.patches[patch].normal;
}

Gatherer::~Gatherer() = default;

Rgb Gatherer::radiosity_at(std::size_t patch, double u, double v) const {
    return interpolate(total_corners_[patch], mesh_.patches[patch].corner_count(), u, v);
}

Rgb Gatherer::reflected_at(std::size_t patch, double u, double v) const {
    return interpolate(reflected_corners_[patch], mesh_.patches[patch].corner_count(), u, v);
}

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
        for (int k = 0; k < p.corner_count(); ++k)
            off = std::max(off, std::abs(dot(mesh_.vertices[p.corners[k]] - point, normal)));
        if (off <= 1e-6 * std::sqrt(p.area)) return 0;
    }
    clipped = ff::clip_to_front(corners_of(mesh_, patch), point, normal);
    if (clipped.size() < 3) return 0;
    const double f = point_to_polygon_form_factor(point, normal, clipped);
    return f > 0 ? f : 0;
}

// The part of `clipped` (of `patch`) the point sees: shadow rays to stratified points,
// weighted by the form-factor kernel, so a half-hidden patch counts by what it contributes.
double Gatherer::visible_fraction(const Vec3& point, const Vec3& normal, std::size_t patch,
                                  const std::vector<Vec3>& clipped, int rays, Rng& rng) const {
    if (rays <= 0) return 1;
    const auto& p = mesh_.patches[patch];
    const auto cdf = ff::fan_cdf(clipped);
    const double offset = rng.uniform();
    double weight_sum = 0, visible_sum = 0, plain_visible = 0;
    for (int s = 0; s < rays; ++s) {
        const double u0 = ff::wrap((s + 0.5) / rays + offset);
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
    return weight_sum > 0 ? visible_sum / weight_sum : plain_visible / rays;
}

// Direct light: every emitting patch's exact form factor, and its visible fraction from a
// budget of shadow rays shared by what each patch contributes (at least one each), so a
// lamp split into many patches costs about as much as one.
Rgb Gatherer::direct(const Vec3& point, const Vec3& normal, std::uint64_t index) const {
    Rng rng(options_.seed ^ 0xD1EC7ull, index);
    struct Seen {
        std::uint32_t patch;
        double form_factor, weight;
        std::vector<Vec3> clipped;
    };
    thread_local std::vector<Seen> seen;
    seen.clear();
    double total = 0;
    std::vector<Vec3> clipped;
    for (const auto j : emitters_) {
        const double f = form_factor_to(point, normal, j, clipped);
        if (f <= 0) continue;
        const auto& e = emission_[j];
        const double weight = f * (e[0] + e[1] + e[2]);
        seen.push_back({j, f, weight, clipped});
        total += weight;
    }
    Rgb sum{0, 0, 0};
    for (const auto& s : seen) {
        const int rays =
            options_.shadow_rays <= 0
                ? 0
                : std::max(1,
                           static_cast<int>(std::lround(options_.shadow_rays * s.weight / total)));
        const double f =
            s.form_factor * visible_fraction(point, normal, s.patch, s.clipped, rays, rng);
        for (int k = 0; k < 3; ++k) sum[k] += emission_[s.patch][k] * f;
    }
    return sum;
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
        const double seen = visible_fraction(point, normal, j, clipped, options_.shadow_rays, rng);
        for (int k = 0; k < 3; ++k) sum[k] += b[k] * f * seen;
    }
    return sum;
}

Irradiance Gatherer::gather(const Vec3& point, const Vec3& normal, std::uint64_t index) const {
    return gather(point, normal, normal, index);
}

Irradiance Gatherer::gather(const Vec3& point, const Vec3& normal, const Vec3& surface,
                            std::uint64_t index) const {
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
        const Vec3 d = stratified_direction(normal, tu, tv, r, rays, rotation);
        if (dot(d, surface) <= 0) continue; // into the surface under a shading normal
        const auto hit = scene_->trace(point, d);
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
