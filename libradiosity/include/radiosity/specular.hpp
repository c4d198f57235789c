// Mirrors and glass (the two-pass method of Wallace, Cohen and Greenberg, 1987): where a ray
// meets a surface with a specular part it goes on, reflected or transmitted, weighted by the
// share that goes that way. Form factors follow these paths (pass 1: light reaches a diffuse
// patch through mirrors and glass), and so do the views and the sensors (pass 2).
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace rad {

// The reflectance of a smooth boundary between media, unpolarised (the mean of Fresnel's s
// and p shares), for a ray meeting it at cos_incident (> 0) from the side of index n1 toward
// index n2. 1 under total internal reflection.
double fresnel_reflectance(double cos_incident, double n1, double n2);

// Radiance's glass: a pane of index `ior` whose transmittance at normal incidence is
// `normal_transmittance` (what a glazing catalogue gives) has this transmissivity (the share
// a ray keeps crossing the glass once, along its normal), from Tn = t (1-r)^2 / (1 - r^2 t^2).
double pane_transmissivity(double normal_transmittance, double ior);
// What such a pane (transmissivity `t`) transmits and reflects of light meeting it at
// cos_incident, both polarisations and every inner reflection summed.
struct PaneShares {
    double transmitted = 0, reflected = 0;
};
PaneShares pane_shares(double transmissivity, double ior, double cos_incident);
// What glass of `specular` lets through of white light by the angle it meets it at: the
// luminous share at cos = 0, 1/steps, ..., 1 (a pane as its rays take it, every reflection
// inside summed; other glass at its normal transmittance). For drawing a beam through it.
std::vector<double> luminous_transmittance_by_angle(const radfmt::Specular& specular, int steps);

// The default number of specular events a path may go through (rad-ff --specular-depth).
inline constexpr int kDefaultSpecularDepth = 12;
// Paths whose weight falls below this (in every channel) end: they carry nothing visible.
inline constexpr double kMinPathWeight = 1e-4;

// One way a ray goes on from a specular surface.
struct SpecularBranch {
    Vec3 direction;
    radfmt::Rgb weight; // the share of light that comes along it, per channel
};

// The specular parts of a mesh's patches, and how rays go on from them.
class SpecularSurfaces {
  public:
    explicit SpecularSurfaces(const radfmt::MeshData& mesh);
    bool any() const { return any_; }
    const radfmt::Specular& of(std::size_t patch) const {
        return mesh_.materials[mesh_.patches[patch].material].specular;
    }
    bool is_specular(std::size_t patch) const { return of(patch).any(); }
    // Light can pass it (a pane or a dielectric): meeting its back is no wrong way.
    bool transmits(std::size_t patch) const;
    // The branches a ray of unit `direction` takes where it meets `patch` (its front when
    // `front`): reflected and transmitted, none for a surface with no specular part.
    // Returns how many (0 to 2) are in `out`. With `hit`, the surface's normal there is its
    // corners' normals interpolated (a faceted sphere mirrors as a sphere).
    int branches(std::size_t patch, const Vec3& direction, bool front,
                 std::array<SpecularBranch, 2>& out, const RayScene::Hit* hit = nullptr) const;
    // The normal at a hit: interpolated over the patch's corners within the crease angle.
    Vec3 normal_at(const RayScene::Hit& hit) const;
    // Its corners' normals are its own: it reflects as the plane it lies in (not a facet of a
    // curved mirror, whose normal is interpolated across it).
    bool flat(std::size_t patch) const;

  private:
    const radfmt::MeshData& mesh_;
    std::vector<radfmt::Rgb> pane_transmissivity_; // per material and channel, for panes
    CornerColours corner_normals_; // the patches' normals at their corners (empty: no specular)
    bool any_ = false;
};

// The planar mirrors of a mesh: mirror and Fresnel patches that are flat (SpecularSurfaces::
// flat), grouped by material and plane (to a millionth of the scene's size). Light sources
// seen in them are taken as their images (virtual sources): the gather's emitters, luminaires.
struct PlanarMirrors {
    struct Plane {
        Vec3 point, normal; // a point on it and its unit normal (the mirror's front)
    };
    std::vector<Plane> planes;
    std::vector<int> plane_of; // per patch: its plane, or -1
    bool empty() const { return planes.empty(); }
    Vec3 mirrored(std::size_t plane, const Vec3& p) const {
        const auto& m = planes[plane];
        return p - m.normal * (2 * dot(p - m.point, m.normal));
    }
    Vec3 mirrored_direction(std::size_t plane, const Vec3& d) const {
        return d - planes[plane].normal * (2 * dot(d, planes[plane].normal));
    }
};
PlanarMirrors planar_mirrors(const radfmt::MeshData& mesh, const SpecularSurfaces& specular);

// What of each channel goes from `from` to `to` in a straight line: 1 unblocked, 0 blocked,
// and through thin panes (up to `max_panes`) their transmission at the angle met.
radfmt::Rgb straight_transmission(const RayScene& scene, const SpecularSurfaces& specular,
                                  const Vec3& from, const Vec3& to, int max_panes);

// What of each channel of a source at `source` reaches `point` by way of mirror `plane`: the
// ray from the point toward the source's image must meet that mirror's front first, the
// reflected segment reach the source unblocked; the mirror's reflectance at that angle, or 0.
radfmt::Rgb via_mirror(const RayScene& scene, const SpecularSurfaces& specular,
                       const PlanarMirrors& mirrors, std::size_t plane, const Vec3& point,
                       const Vec3& source);

// A surface a path reached: the hit, the weight of the light that comes from it along the
// path, and how many specular events came before it (0: the first surface the ray met).
struct PathHit {
    RayScene::Hit hit;
    radfmt::Rgb weight;
    int events = 0;
    Vec3 origin, direction; // of the path's last segment
    std::int64_t from = -1; // the patch of the last specular event (-1: none)
    bool straight = true;   // every event let the ray through unturned (thin panes)
};

// Follows a ray from `origin` along unit `direction` through up to `depth` specular events,
// branching where glass both reflects and transmits, and calls visit(const PathHit&) for
// every surface reached (specular ones too: their diffuse part is seen), and
// escape(const Vec3& direction, const radfmt::Rgb& weight) for every path that leaves the
// scene (to the sky). Deterministic: no random numbers. `weight` is the ray's own (1 for a
// form factor).
template <class Visit, class Escape>
void follow_specular(const RayScene& scene, const SpecularSurfaces& surfaces, const Vec3& origin,
                     const Vec3& direction, const radfmt::Rgb& weight, int depth, Visit&& visit,
                     Escape&& escape) {
    struct Segment {
        Vec3 origin, direction;
        radfmt::Rgb weight;
        int events;
        std::int64_t from;
        bool straight;
    };
    std::vector<Segment> stack{{origin, direction, weight, 0, -1, true}};
    while (!stack.empty()) {
        const Segment s = stack.back();
        stack.pop_back();
        const auto hit = scene.trace(s.origin, s.direction);
        if (hit.patch < 0) {
            escape(s.direction, s.weight);
            continue;
        }
        visit(PathHit{hit, s.weight, s.events, s.origin, s.direction, s.from, s.straight});
        const auto patch = static_cast<std::size_t>(hit.patch);
        if (s.events >= depth || !surfaces.is_specular(patch)) continue;
        std::array<SpecularBranch, 2> next;
        const int count = surfaces.branches(patch, s.direction, hit.front, next, &hit);
        const Vec3 at = s.origin + s.direction * hit.distance;
        for (int b = 0; b < count; ++b) {
            radfmt::Rgb w;
            bool alive = false;
            for (int c = 0; c < 3; ++c) {
                w[c] = s.weight[c] * next[b].weight[c];
                alive = alive || w[c] >= kMinPathWeight;
            }
            const bool unturned = dot(next[b].direction, s.direction) > 1 - 1e-12;
            if (alive)
                stack.push_back(
                    {at, next[b].direction, w, s.events + 1, hit.patch, s.straight && unturned});
        }
    }
}

// The same, for callers that do not look past the scene.
template <class Visit>
void follow_specular(const RayScene& scene, const SpecularSurfaces& surfaces, const Vec3& origin,
                     const Vec3& direction, const radfmt::Rgb& weight, int depth, Visit&& visit) {
    follow_specular(scene, surfaces, origin, direction, weight, depth, std::forward<Visit>(visit),
                    [](const Vec3&, const radfmt::Rgb&) {});
}

} // namespace rad
