// The optics of smooth surfaces: Fresnel's boundary, Radiance's glass pane, and the branches
// a ray takes at a mirror or glass.
#include "radiosity/specular.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace rad {

double fresnel_reflectance(double cos_incident, double n1, double n2) {
    const double ci = std::clamp(cos_incident, 0.0, 1.0);
    const double eta = n1 / n2;
    const double sin2_t = eta * eta * (1 - ci * ci);
    if (sin2_t >= 1) return 1; // total internal reflection
    const double ct = std::sqrt(1 - sin2_t);
    const double rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    const double rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    return 0.5 * (rs * rs + rp * rp);
}

double pane_transmissivity(double tn, double ior) {
    if (tn <= 0) return 0;
    const double r = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    const double a = (1 - r) * (1 - r);
    // Tn r^2 t^2 + (1-r)^2 t - Tn = 0, the positive root (t -> Tn / (1-r)^2 as r -> 0).
    if (r == 0) return std::min(1.0, tn);
    const double t = (-a + std::sqrt(a * a + 4 * tn * tn * r * r)) / (2 * tn * r * r);
    return std::min(1.0, t);
}

std::vector<double> luminous_transmittance_by_angle(const radfmt::Specular& s, int steps) {
    std::vector<double> table;
    for (int k = 0; k <= steps; ++k) {
        radfmt::Rgb t{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c)
            t[c] = s.kind == radfmt::SpecularKind::pane
                       ? pane_shares(pane_transmissivity(s.transmittance[c], s.ior), s.ior,
                                     double(k) / steps)
                             .transmitted
                       : s.transmittance[c];
        table.push_back(luminous(t));
    }
    return table;
}

PaneShares pane_shares(double t, double ior, double cos_incident) {
    const double ci = std::clamp(cos_incident, 1e-9, 1.0);
    const double sin2_t = (1 - ci * ci) / (ior * ior);
    const double ct = std::sqrt(1 - sin2_t);
    // The ray crosses the glass along a path 1/ct times its thickness.
    const double path_t = t > 0 ? std::pow(t, 1 / ct) : 0;
    const double rs = std::pow((ci - ior * ct) / (ci + ior * ct), 2);
    const double rp = std::pow((ior * ci - ct) / (ior * ci + ct), 2);
    PaneShares out;
    for (const double r : {rs, rp}) {
        const double inner = 1 - r * r * path_t * path_t; // the inner reflections' series
        out.transmitted += 0.5 * (1 - r) * (1 - r) * path_t / inner;
        out.reflected += 0.5 * (r + (1 - r) * (1 - r) * r * path_t * path_t / inner);
    }
    return out;
}

SpecularSurfaces::SpecularSurfaces(const radfmt::MeshData& mesh)
    : mesh_(mesh), any_(mesh.has_specular()) {
    for (const auto& m : mesh.materials) {
        radfmt::Rgb t{};
        for (int c = 0; c < 3; ++c)
            t[c] = pane_transmissivity(m.specular.transmittance[c], m.specular.ior);
        pane_transmissivity_.push_back(t);
    }
    if (!any_) return;
    std::vector<radfmt::Rgb> normals;
    normals.reserve(mesh.patches.size());
    for (const auto& p : mesh.patches) normals.push_back({p.normal[0], p.normal[1], p.normal[2]});
    corner_normals_ = corner_colours(mesh, normals, Smoothing::Crease, 30);
}

bool SpecularSurfaces::transmits(std::size_t patch) const {
    return of(patch).transmits();
}

namespace {
Vec3 mirrored(const Vec3& d, const Vec3& n) {
    return d - n * (2 * dot(d, n));
}
radfmt::Rgb grey(double x) {
    return radfmt::Rgb{{x, x, x}};
}
} // namespace

Vec3 SpecularSurfaces::normal_at(const RayScene::Hit& hit) const {
    const auto& flat = mesh_.patches[static_cast<std::size_t>(hit.patch)].normal;
    if (corner_normals_.patches.empty()) return flat;
    const auto c = interpolate_corners(mesh_, corner_normals_, hit.patch, hit.u, hit.v, hit.piece);
    const Vec3 n{c[0], c[1], c[2]};
    const double len = length(n);
    // Interpolated normals stay on the patch's side of its plane.
    if (!(len > 0) || dot(n, flat) <= 0.5 * len) return flat;
    return n * (1 / len);
}

bool SpecularSurfaces::flat(std::size_t patch) const {
    if (corner_normals_.patches.empty()) return true;
    const auto& n = mesh_.patches[patch].normal;
    for (int k = 0; k < mesh_.patches[patch].corner_count(); ++k) {
        const auto& c = corner_normals_.at(mesh_, patch, static_cast<std::size_t>(k));
        const Vec3 v{c[0], c[1], c[2]};
        const double len = length(v);
        if (!(len > 0) || dot(v, n) < (1 - 1e-9) * len) return false;
    }
    return true;
}

int SpecularSurfaces::branches(std::size_t patch, const Vec3& d, bool front,
                               std::array<SpecularBranch, 2>& out, const RayScene::Hit* hit) const {
    using radfmt::SpecularKind;
    const auto& material = mesh_.materials[mesh_.patches[patch].material];
    const auto& s = material.specular;
    const Vec3& flat = mesh_.patches[patch].normal;
    Vec3 n = hit ? normal_at(*hit) : flat;
    // A ray must meet the shading normal from the side it met the patch.
    if ((dot(d, n) < 0) != front) n = flat;
    const double cos_i = std::min(1.0, std::abs(dot(d, n)));
    switch (s.kind) {
    case SpecularKind::none:
        return 0;
    case SpecularKind::mirror:
        // A mirror's back is its backing, not a mirror.
        if (!front) return 0;
        out[0] = {mirrored(d, n), s.reflectance};
        return 1;
    case SpecularKind::fresnel: {
        if (!front) return 0;
        // Schlick's approximation from the reflectance at normal incidence.
        const double rise = std::pow(1 - cos_i, 5);
        out[0].direction = mirrored(d, n);
        for (int c = 0; c < 3; ++c)
            out[0].weight[c] = s.reflectance[c] + (1 - s.reflectance[c]) * rise;
        return 1;
    }
    case SpecularKind::pane: {
        out[0].direction = d;
        out[1].direction = mirrored(d, n);
        for (int c = 0; c < 3; ++c) {
            const auto shares =
                pane_shares(pane_transmissivity_[mesh_.patches[patch].material][c], s.ior, cos_i);
            out[0].weight[c] = shares.transmitted;
            out[1].weight[c] = shares.reflected;
        }
        return 2;
    }
    case SpecularKind::dielectric: {
        // The medium is behind the surface's back: a ray meeting the front enters it.
        const double n1 = front ? 1.0 : s.ior, n2 = front ? s.ior : 1.0;
        // The diffuse part takes its share first; the boundary splits the rest.
        const auto& kd = material.reflectance;
        const double share = 1 - std::max({kd[0], kd[1], kd[2]});
        const double r = fresnel_reflectance(cos_i, n1, n2);
        out[0] = {mirrored(d, n), grey(share * r)};
        if (r >= 1) return 1;
        const double eta = n1 / n2;
        const double cos_t = std::sqrt(std::max(0.0, 1 - eta * eta * (1 - cos_i * cos_i)));
        const Vec3 toward = dot(d, n) < 0 ? n : n * -1.0; // the normal on the ray's side
        out[1].direction = normalized(d * eta + toward * (eta * cos_i - cos_t));
        // Radiance scales by (n1/n2)^2 across the boundary: light entering a denser medium
        // is squeezed into a narrower cone (the path is traced from the receiver back).
        // The filter (MTL's Tf) is what a passage through the solid keeps: its square root
        // at each of the two crossings, in either direction, so paths stay reciprocal.
        const double squeeze = eta * eta;
        for (int c = 0; c < 3; ++c)
            out[1].weight[c] = share * (1 - r) * squeeze * std::sqrt(s.transmittance[c]);
        return 2;
    }
    }
    return 0;
}

PlanarMirrors planar_mirrors(const radfmt::MeshData& mesh, const SpecularSurfaces& specular) {
    PlanarMirrors out;
    out.plane_of.assign(mesh.patches.size(), -1);
    if (!specular.any()) return out;
    const double size = std::max(1e-300, bounds(mesh.vertices).diagonal());
    std::map<std::tuple<std::uint32_t, long long, long long, long long, long long>, int> plane_of;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        if (!specular.of(i).mirrors() || !specular.flat(i)) continue;
        const auto& p = mesh.patches[i];
        const auto q = [](double x) { return std::llround(x * 1e6); };
        const auto key = std::make_tuple(p.material, q(p.normal[0]), q(p.normal[1]), q(p.normal[2]),
                                         q(dot(p.centroid, p.normal) / size));
        const auto [at, added] = plane_of.try_emplace(key, static_cast<int>(out.planes.size()));
        if (added) out.planes.push_back({p.centroid, p.normal});
        out.plane_of[i] = at->second;
    }
    return out;
}

radfmt::Rgb straight_transmission(const RayScene& scene, const SpecularSurfaces& specular,
                                  const Vec3& from, const Vec3& to, int max_panes) {
    if (!specular.any()) return scene.visible(from, to) ? grey(1) : grey(0);
    radfmt::Rgb kept = grey(1);
    Vec3 origin = from;
    const Vec3 d = to - from;
    const double distance = length(d);
    if (!(distance > 0)) return kept;
    const Vec3 dir = d * (1 / distance);
    double left = distance;
    std::array<SpecularBranch, 2> branch;
    for (int crossed = 0; crossed <= max_panes; ++crossed) {
        if (scene.visible(origin, origin + dir * left)) return kept;
        const auto hit = scene.trace(origin, dir);
        if (hit.patch < 0 || hit.distance >= left) return kept; // grazing the target itself
        const auto patch = static_cast<std::size_t>(hit.patch);
        if (specular.of(patch).kind != radfmt::SpecularKind::pane) return grey(0);
        if (specular.branches(patch, dir, hit.front, branch) < 1) return grey(0);
        for (int c = 0; c < 3; ++c) kept[c] *= branch[0].weight[c]; // the straight branch
        origin = origin + dir * hit.distance;
        left -= hit.distance;
    }
    return grey(0);
}

radfmt::Rgb via_mirror(const RayScene& scene, const SpecularSurfaces& specular,
                       const PlanarMirrors& mirrors, std::size_t plane, const Vec3& point,
                       const Vec3& source) {
    const Vec3 image = mirrors.mirrored(plane, source);
    const Vec3 d = image - point;
    const double distance = length(d);
    if (!(distance > 0)) return grey(0);
    const Vec3 dir = d * (1 / distance);
    const auto hit = scene.trace(point, dir);
    if (hit.patch < 0 || mirrors.plane_of[static_cast<std::size_t>(hit.patch)] != int(plane) ||
        !hit.front || hit.distance >= distance)
        return grey(0);
    const Vec3 on_mirror = point + dir * hit.distance;
    std::array<SpecularBranch, 2> branch;
    if (!scene.visible(on_mirror, source) ||
        specular.branches(static_cast<std::size_t>(hit.patch), dir, true, branch) < 1)
        return grey(0);
    return branch[0].weight;
}

} // namespace rad
