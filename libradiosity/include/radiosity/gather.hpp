// Final gather: the irradiance arriving at any point from a solved scene, with rays cast
// from the point itself, so shadows and gradients are as sharp as the geometry (not as
// coarse as the patches). Direct light is taken from the lights explicitly: the emitters, and
// patches so bright that rays landing on them would make fireflies. They sit in a light tree,
// so a point pays for the lights near it, not for all of them: a near light by its exact
// point-to-polygon form factor, a far group of lights as one, each times the visible fraction
// from shadow rays shared by what each contributes. Indirect light comes from cosine-weighted
// rays, each taking the reflected radiosity (B - E) where it lands (nothing on a bright
// patch: that is direct light), interpolated over the patch as rad-shade's smoothing does
// and scaled so that each patch keeps its mean (keep_patch_means);
// or (exact) the point-to-polygon sum over every patch.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rad {
namespace gather {
class LightTree;
class VirtualSources;
} // namespace gather

struct GatherOptions {
    int rays = 256; // indirect: cosine-weighted rays per point
    // Direct: shadow rays per point for the emitters' visible fractions, shared among the
    // emitting patches by what each contributes (at least one each); --exact: per patch.
    int shadow_rays = 32;
    // Lights whose bounding sphere's radius is under this fraction of their distance are taken
    // as one (relative error about its square); 0 (and `exact`): every light on its own.
    double cluster_ratio = 0.1;
    // A group of lights dim at a point is taken as one up to half its distance across when the
    // error it can bring, its irradiance x (radius / distance)^2, is under this share of the
    // point's whole direct light (roughly estimated first): a room's far lamps cost a few
    // clusters, not hundreds. 0 (or a cluster_ratio of 0): only cluster_ratio decides.
    double cluster_tolerance = 2e-5;
    // Patches whose reflected radiosity (r + g + b) exceeds this many times the area-weighted
    // mean over the scene are lights, not left to the indirect rays (a ray that lands on a
    // small very bright patch is a firefly); 0: none. Not with `exact`, which has no rays.
    double bright_factor = 8;
    bool exact = false;     // indirect as the point-to-polygon sum over every patch
    std::uint64_t seed = 1; // each point has its own stream: (seed, point index)
    Smoothing smoothing = Smoothing::Crease;
    double crease_deg = 30;
    // A point whose rays meet the back of surfaces more often than this is inside an object
    // or behind a surface: refused (its value would be meaningless).
    double max_back_fraction = 0.5;
    // Mirrors and glass: indirect rays go on through up to this many specular events.
    int specular_depth = 12; // kDefaultSpecularDepth
    // The error bar: `rays` and `shadow_rays` are cast in this many independent batches, each
    // with its own random turn of the stratified patterns; their spread gives the standard
    // error (batch_error.hpp). 1 (and `exact`): no error is estimated (NaN).
    int batches = 16;
    // Sampling to a stated accuracy: more batches until the illuminance's standard error is
    // at most this share of it, or `max_rays` indirect rays (in proportion: shadow rays) have
    // been cast; 0: exactly `rays`, whatever the error.
    double accuracy = 0.01;
    int max_rays = 4096;
};

struct Irradiance {
    Rgb direct{0, 0, 0}, indirect{0, 0, 0};
    // The standard error of total() per channel and of its luminous value (NaN: not
    // estimated), the indirect rays cast, and whether the point stopped at --max-rays before
    // meeting the accuracy asked for.
    Rgb error{0, 0, 0};
    double luminous_error = 0;
    int rays_cast = 0;
    bool at_budget = false;
    // Of the rays cast from the point, the share that met a surface, and of those the share
    // that met the back of one.
    double hit_fraction = 0, back_fraction = 0;
    // The point is inside an object or behind a surface: most of what it sees are backs
    // (and they are not a sliver of an otherwise open view).
    bool sees_backs(double max_back_fraction) const {
        return sees_mostly_backs(hit_fraction, back_fraction, max_back_fraction);
    }
    Rgb total() const {
        return {direct[0] + indirect[0], direct[1] + indirect[1], direct[2] + indirect[2]};
    }
};

class Gatherer {
  public:
    // `radiosity` is B per patch (the solution); `mesh` carries the E and rho it was solved
    // with (see apply_recorded_overrides).
    Gatherer(const radfmt::MeshData& mesh, std::span<const Rgb> radiosity, GatherOptions options);
    ~Gatherer();

    // Irradiance (W/m^2) at `point` on a sensor facing `normal` (unit); `index` seeds the
    // point's random stream. When the result sees_backs(options.max_back_fraction), the
    // point is inside an object or behind a surface: the caller refuses it.
    // `known` is light the caller adds exactly (the luminaires'): it has no error, and counts
    // in the accuracy's relative target.
    Irradiance gather(const Vec3& point, const Vec3& normal, std::uint64_t index,
                      const Rgb& known = {0, 0, 0}) const;
    // On a surface shaded with an interpolated normal: rays below the surface's own plane
    // (`surface`, its geometric normal) go into it, and count as nothing.
    Irradiance gather(const Vec3& point, const Vec3& normal, const Vec3& surface,
                      std::uint64_t index, const Rgb& known = {0, 0, 0}) const;
    // The direct light alone, its shadow rays in one set (no error bar), for a view whose
    // indirect light comes from an irradiance cache, at points close together on one surface
    // (a pixel's samples on one patch): the lights they see, and what each gives unshadowed,
    // found once from `centre` facing `facing` (unit; the points' mean: most of a point's cost
    // where lights are many); each point then shadowed from itself with its own stream
    // (`index`). out[k] is samples[k]'s.
    struct DirectSample {
        Vec3 point, normal;
        std::uint64_t index = 0;
    };
    // With `kept`: which lights the points see is taken from it when it holds a cut (each
    // light's and group's light still found at `centre`), and put in it when not. For
    // neighbouring pixels on one surface, whose cuts would differ by nothing or by a group
    // opened one level more or less.
    struct KeptCut {
        std::vector<std::uint32_t> lights, clusters; // the light tree's lights and nodes
        bool held = false;
    };
    // A light or group of lights a point sees, with the irradiance it gives there unshadowed.
    struct Seen {
        bool cluster = false;
        std::uint32_t id = 0;    // the patch of a single light, the tree node of a cluster
        std::uint32_t order = 0; // its (first) light's place in the light tree: a cut's order
        Rgb irradiance{0, 0, 0};
        double weight = 0;         // brightness(irradiance): its share of the shadow rays
        std::vector<Vec3> clipped; // a single light: its part in front of the point
    };
    // What the lights give at one point, unshadowed: `lights[0, count)`, their weights'
    // `total` (the buffers kept between points).
    struct SeenLights {
        std::vector<Seen> lights;
        std::size_t count = 0;
        double total = 0;
        std::span<Seen> seen() { return {lights.data(), count}; }
    };
    // The lights seen from `centre` facing `facing` (unit), into `out`; `kept` as in
    // direct_light below.
    void seen_lights(const Vec3& centre, const Vec3& facing, SeenLights& out,
                     KeptCut* kept = nullptr) const;
    // The same at `point` between two points of one surface where `a` and `b` were found,
    // `share` of the way from a's to b's, in a's cut: each light or group that b holds too
    // blended linearly between their values (a's clipped polygon), the others found there.
    // What a light gives unshadowed is smooth along a surface: between neighbouring pixels
    // this saves most exact form factors.
    void seen_between(const SeenLights& a, const SeenLights& b, double share, const Vec3& point,
                      const Vec3& normal, SeenLights& out) const;
    // Each sample shadowed from its own point with its own stream, from what `seen` gives.
    void direct_light(SeenLights& seen, std::span<const DirectSample> samples,
                      std::span<Rgb> out) const;
    void direct_light(const Vec3& centre, const Vec3& facing, std::span<const DirectSample> samples,
                      std::span<Rgb> out, KeptCut* kept = nullptr) const;
    // An irradiance cache's record: the indirect light from about `rays` cosine-weighted rays,
    // one in each cell of a theta x phi grid (`surface` as in gather()), the harmonic mean and
    // the least distance of what they met (Ward, Rubinstein and Clear 1988: how far the
    // indirect light may be reused), and its gradients (Ward and Heckbert 1992). Not for
    // meshes with mirrors or glass.
    struct IndirectSample {
        Rgb indirect{0, 0, 0};
        double harmonic_distance = 0;                      // 0: nothing was met
        double nearest = 0;                                // 0: nothing was met
        std::array<Vec3, 3> translational{}, rotational{}; // see IrradianceGradients
    };
    IndirectSample indirect_sample(const Vec3& point, const Vec3& normal, const Vec3& surface,
                                   int rays, std::uint64_t index) const;
    // The normal where a ray hit a patch, interpolated from its corners (smoothed over
    // neighbours of its material within the crease angle; the patch's own when flat).
    Vec3 shading_normal(const RayScene::Hit& hit) const;

    const radfmt::MeshData& mesh() const { return mesh_; }
    const RayScene& scene() const { return *scene_; }
    const SpecularSurfaces& specular() const { return *specular_; }
    // Its planar mirrors (luminaires are seen in them as images too).
    const PlanarMirrors& mirrors() const;
    int specular_depth() const { return options_.specular_depth; }
    const GatherOptions& options() const { return options_; }
    // Patches sampled as lights because they reflect so much (see bright_factor).
    std::size_t bright_patches() const;
    // The radiosity where a ray hit a patch, interpolated as rad-shade.
    Rgb radiosity_at(const RayScene::Hit& hit) const;
    // The reflected part B - E, interpolated the same way.
    Rgb reflected_at(const RayScene::Hit& hit) const;

  private:
    struct Evidence;
    void find_bright_patches();
    void build_light_tree();
    // Single light `light` (of the light tree's lights) seen from the point, into `s`: its
    // exact form factor (returned; 0 when the point is behind it) times its radiosity.
    double value_light(std::uint32_t light, const Vec3& point, const Vec3& normal, Seen& s) const;
    // One batch: the indirect light of `rays` rays (`evidence` counts what they hit).
    Rgb indirect_batch(const Vec3& point, const Vec3& normal, const Vec3& surface, int rays,
                       Rng& rng, Evidence& evidence) const;
    Rgb cast_indirect(const Vec3& point, const Vec3& normal, const Vec3& surface, int rays,
                      Rng& rng, Evidence& evidence) const;
    // How `budget` shadow rays are shared among what a point sees (by what each gives): the
    // lights and groups with rays of their own, and the pool of the rest.
    struct ShadowShares {
        std::vector<std::pair<const Seen*, int>> own; // each with its rays
        std::vector<const Seen*> pooled;
        double pooled_weight = 0;
        Rgb pooled_sum{0, 0, 0};
        int pooled_rays = 0;
    };
    void share_shadow_rays(std::span<Seen> seen, double total, int budget, ShadowShares& out) const;
    // One batch: the direct light of what a point sees, its shadow rays shared as `shares`.
    Rgb direct_batch(const Vec3& point, const Vec3& normal, const ShadowShares& shares,
                     int shadow_rays, Rng& rng) const;
    Rgb shadowed(const Vec3& point, const Vec3& normal, const ShadowShares& shares, Rng& rng) const;
    Rgb cluster_visible_fraction(const Vec3& point, const Vec3& normal, std::uint32_t node,
                                 int rays, Rng& rng) const;
    Rgb pooled_visible_fraction(const Vec3& point, std::span<const Seen* const> pooled,
                                double weight, int rays, Rng& rng) const;
    Rgb seen_through(const Vec3& from, const Vec3& to) const;
    Vec3 point_on_light(std::size_t patch, double u, Rng& rng) const;
    Rgb exact_indirect(const Vec3& point, const Vec3& normal, std::uint64_t index) const;
    // What an indirect ray from a point brings through mirrors and glass (its first surface
    // as reflected light; what it reaches beyond, emission included); counts its hits.
    Rgb specular_ray(const Vec3& point, const Vec3& d, int& hits, int& backs) const;
    // What a ray meeting no mirror or glass brings back: the light reflected where it lands
    // (none from a back, nor from a light: the direct light's), and how far it went (0: it
    // met nothing).
    struct RayReturn {
        Rgb radiance{0, 0, 0};
        double distance = 0;
        bool back = false;
    };
    RayReturn diffuse_ray(const Vec3& point, const Vec3& d) const;
    double form_factor_to(const Vec3& point, const Vec3& normal, std::size_t patch,
                          std::vector<Vec3>& clipped) const;
    Rgb visible_fraction(const Vec3& point, const Vec3& normal, std::size_t patch,
                         const std::vector<Vec3>& clipped, int rays, Rng& rng) const;

    const radfmt::MeshData& mesh_;
    GatherOptions options_;
    std::unique_ptr<RayScene> scene_;
    std::unique_ptr<SpecularSurfaces> specular_;      // mirrors and glass
    std::vector<Rgb> emission_;                       // E per patch
    CornerColours total_corners_;                     // B at the corners
    CornerColours reflected_corners_;                 // B - E at the corners
    std::vector<Rgb> reflected_flat_;                 // B - E per patch
    std::vector<std::uint8_t> bright_;                // lit so much it is a light
    std::unique_ptr<gather::LightTree> lights_;       // emitters and bright patches
    std::unique_ptr<gather::VirtualSources> virtual_; // emitters seen in planar mirrors
    CornerColours corner_normals_;                    // smoothed normals at the corners
    std::vector<double> quad_first_share_; // a quad's first fan triangle's share of its area
};

// Luminous efficacy of Radiance's white (lm/W) and its RGB luminance weights: illuminance
// in lux = 179 x (0.265 R + 0.670 G + 0.065 B) for irradiance R, G, B in W/m^2.
inline constexpr double kRadianceEfficacy = 179;
inline double lux(const Rgb& irradiance) {
    return kRadianceEfficacy * luminous(irradiance);
}

} // namespace rad
