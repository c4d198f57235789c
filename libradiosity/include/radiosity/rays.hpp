// Embree 3 scene over the patches of a mesh: built once, then queried from many threads.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <cstdint>
#include <memory>

namespace rad {

class RayScene {
  public:
    explicit RayScene(const radfmt::MeshData& mesh);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // True when nothing blocks the open segment from `from` to `to`.
    bool visible(const Vec3& from, const Vec3& to) const;
    // The patch hit first along the ray, or -1 when it escapes; `front` tells whether the
    // ray met the patch's front side.
    std::int64_t first_hit(const Vec3& origin, const Vec3& direction, bool& front) const;
    double epsilon() const { return epsilon_; }

    struct Impl; // public so Embree's C error callback can reach it

  private:
    std::unique_ptr<Impl> impl_;
    double epsilon_ = 1e-6;
};

} // namespace rad
