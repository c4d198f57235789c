// Embree 3 scene over the patches of a mesh: built once, then queried from many threads.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace rad {

// Refuses (InputError naming `source`) points that rays cannot resolve: Embree computes in
// single precision, with products of three coordinates, so a scene must be between
// kMinRaySceneSize and kMaxRaySceneSize across; and it must sit within kMaxRaySceneOffset
// of its own size from the origin, or double precision loses its detail before the ray
// scene (which recentres it) sees it.
inline constexpr double kMinRaySceneSize = 1e-11, kMaxRaySceneSize = 1e13;
inline constexpr double kMaxRaySceneOffset = 1e9;
void check_ray_precision(std::span<const radfmt::Vec3> points, const std::string& source);

// Rays from a point farther than this many scene sizes from the scene cannot be traced in
// single precision (Embree aborts on some): every tool that casts rays from a position it is
// given (a sensor, a grid's corner, a camera) asks out_of_reach first.
inline constexpr double kMaxRayOriginDistance = 1e6;
// Why rays from `p` cannot be traced in the scene in `box`, or "" when they can (a non-finite
// point cannot either).
std::string out_of_reach(const Vec3& p, const Box& box);

// What rays cast from a point say of where it is: inside an object, under something or
// behind a surface when more than `max_back_fraction` of the surfaces they meet show their
// back, and those backs are not a sliver of an open view (at least a tenth of all the rays).
// `hit_fraction`: of the rays, those that met a surface; `back_fraction`: of those, backs.
inline bool sees_mostly_backs(double hit_fraction, double back_fraction,
                              double max_back_fraction = 0.5) {
    return back_fraction > max_back_fraction && back_fraction * hit_fraction >= 0.1;
}

// How much work building a RayScene's tree may take: Fast for a few rays per patch (the mesh
// stage's checks), Quality for millions (form factors, images).
enum class RayBuild { Fast, Quality };

class RayScene {
  public:
    explicit RayScene(const radfmt::MeshData& mesh, RayBuild build = RayBuild::Quality);
    // The same, releasing the mesh's patches and vertices before the tree is built (the
    // build's peak of memory), for a mesh made only to be traced.
    explicit RayScene(radfmt::MeshData&& mesh, RayBuild build = RayBuild::Quality);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // True when nothing blocks the open segment from `from` to `to`.
    bool visible(const Vec3& from, const Vec3& to) const;
    // The patch hit first along the ray, or -1 when it escapes; `front` tells whether the
    // ray met the patch's front side.
    std::int64_t first_hit(const Vec3& origin, const Vec3& direction, bool& front) const;
    // The same, with where the ray met the patch: its parameters (u along corner 1 - corner
    // 0, v along corner 3 - corner 0 for a quad, bilinear; barycentric weights of corners 1
    // and 2 for a triangle; for a polygon, those of the second and third corner of its
    // triangle `piece`, patch_triangles' numbering) and the distance.
    struct Hit {
        std::int64_t patch = -1; // -1: the ray escaped
        bool front = false;
        double u = 0, v = 0, distance = 0;
        std::int32_t piece = -1; // polygons only
    };
    Hit trace(const Vec3& origin, const Vec3& direction) const;
    double epsilon() const { return epsilon_; }

    struct Impl; // public so Embree's C error callback can reach it

  private:
    // The device, the scene and its geometry from the mesh; returns the scene's size.
    double add_geometry(const radfmt::MeshData& mesh, RayBuild build);
    void commit(double size);

    std::unique_ptr<Impl> impl_;
    double epsilon_ = 1e-6;
    // Embree works in float: coordinates are stored relative to the scene's centre, so a
    // scene far from the origin (georeferenced, say) keeps float's resolution where it is.
    Vec3 centre_{0, 0, 0};
};

} // namespace rad
