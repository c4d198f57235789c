// Emitters seen in planar mirrors (internal header): Radiance's virtual light sources. Each
// emitting patch mirrored through a planar mirror's plane is a light of its own, seen only
// through that mirror's patches: its exact point-to-polygon form factor, times the share of
// shadow rays (weighted by the form-factor kernel) that meet the mirror on the way and then
// reach the emitter unblocked, each times the mirror's reflectance at its angle. A point then
// finds a lamp in a mirror deterministically, as it finds the lamp itself, instead of by the
// indirect rays that happen to land on its image.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/vec.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace rad::gather {

class VirtualSources {
  public:
    // The planar mirrors of `mesh` (mirror and Fresnel patches that are flat, grouped by
    // plane) and its emitting patches (`emission` per patch).
    VirtualSources(const radfmt::MeshData& mesh, const SpecularSurfaces& specular,
                   std::span<const Rgb> emission);
    bool empty() const { return mirrors_.empty() || emitters_.empty(); }
    const PlanarMirrors& mirrors() const { return mirrors_; }
    // `patch` belongs to a planar mirror whose emitters' images are taken here: a path that
    // turns on it once and reaches an emitter brings that emitter's light twice otherwise.
    bool images(std::size_t patch) const {
        return !emitters_.empty() && mirrors_.plane_of[patch] >= 0;
    }
    // The irradiance at `point` (facing unit `normal`) from every emitter's image in every
    // planar mirror, with `rays` shadow rays per mirror shared among its images by what each
    // gives unshadowed.
    Rgb irradiance(const Vec3& point, const Vec3& normal, const RayScene& scene, int rays,
                   Rng& rng) const;

  private:
    struct Image {
        std::vector<Vec3> clipped; // the mirrored emitter, clipped to the point's front
        std::vector<double> cdf;   // its fan's, for points on it (ff::fan_cdf)
        Vec3 normal{};             // the side it shines from
        Rgb irradiance{0, 0, 0};   // unshadowed
        double weight = 0;
    };
    Rgb through_mirror(const Vec3& point, const Vec3& normal, std::size_t plane,
                       std::span<const Image> images, double total, const RayScene& scene, int rays,
                       Rng& rng) const;

    const radfmt::MeshData& mesh_;
    const SpecularSurfaces& specular_;
    PlanarMirrors mirrors_;
    std::vector<std::uint32_t> emitters_;
    std::vector<Rgb> emission_; // of each emitter
};

} // namespace rad::gather
