// Final gather: the irradiance arriving at any point from a solved scene, with rays cast
// from the point itself, so shadows and gradients are as sharp as the geometry (not as
// coarse as the patches). Direct light is taken from the emitters explicitly (exact
// point-to-polygon form factor times the visible fraction from shadow rays); indirect light
// from cosine-weighted rays, each taking the reflected radiosity (B - E) where it lands,
// interpolated over the patch as rad-shade's smoothing does; or (exact) the point-to-polygon
// sum over every patch.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rad {

struct GatherOptions {
    int rays = 256; // indirect: cosine-weighted rays per point
    // Direct: shadow rays per point for the emitters' visible fractions, shared among the
    // emitting patches by what each contributes (at least one each); --exact: per patch.
    int shadow_rays = 32;
    bool exact = false;     // indirect as the point-to-polygon sum over every patch
    std::uint64_t seed = 1; // each point has its own stream: (seed, point index)
    Smoothing smoothing = Smoothing::Crease;
    double crease_deg = 30;
    // A point whose rays meet the back of surfaces more often than this is inside an object
    // or behind a surface: refused (its value would be meaningless).
    double max_back_fraction = 0.5;
};

struct Irradiance {
    Rgb direct{0, 0, 0}, indirect{0, 0, 0};
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
    Irradiance gather(const Vec3& point, const Vec3& normal, std::uint64_t index) const;
    // On a surface shaded with an interpolated normal: rays below the surface's own plane
    // (`surface`, its geometric normal) go into it, and count as nothing.
    Irradiance gather(const Vec3& point, const Vec3& normal, const Vec3& surface,
                      std::uint64_t index) const;
    // The normal at (u, v) of a patch interpolated from its corners (smoothed over
    // neighbours of its material within the crease angle; the patch's own when flat).
    Vec3 shading_normal(std::size_t patch, double u, double v) const;

    const radfmt::MeshData& mesh() const { return mesh_; }
    const RayScene& scene() const { return *scene_; }
    // The radiosity of patch `patch` at its parameters (u, v), interpolated as rad-shade.
    Rgb radiosity_at(std::size_t patch, double u, double v) const;
    // The reflected part B - E, interpolated the same way.
    Rgb reflected_at(std::size_t patch, double u, double v) const;

  private:
    Rgb direct(const Vec3& point, const Vec3& normal, std::uint64_t index) const;
    Rgb exact_indirect(const Vec3& point, const Vec3& normal, std::uint64_t index) const;
    double form_factor_to(const Vec3& point, const Vec3& normal, std::size_t patch,
                          std::vector<Vec3>& clipped) const;
    double visible_fraction(const Vec3& point, const Vec3& normal, std::size_t patch,
                            const std::vector<Vec3>& clipped, int rays, Rng& rng) const;

    const radfmt::MeshData& mesh_;
    GatherOptions options_;
    std::unique_ptr<RayScene> scene_;
    std::vector<Rgb> emission_;                         // E per patch
    std::vector<std::array<Rgb, 4>> total_corners_;     // B at the corners
    std::vector<std::array<Rgb, 4>> reflected_corners_; // B - E at the corners
    std::vector<Rgb> reflected_flat_;                   // B - E per patch
    std::vector<std::uint32_t> emitters_;               // patches with E > 0
    std::vector<std::array<Rgb, 4>> corner_normals_;    // smoothed normals at the corners
};

// Luminous efficacy of Radiance's white (lm/W) and its RGB luminance weights: illuminance
// in lux = 179 x (0.265 R + 0.670 G + 0.065 B) for irradiance R, G, B in W/m^2.
inline constexpr double kRadianceEfficacy = 179;
inline double lux(const Rgb& irradiance) {
    return kRadianceEfficacy *
           (0.265 * irradiance[0] + 0.670 * irradiance[1] + 0.065 * irradiance[2]);
}

} // namespace rad
