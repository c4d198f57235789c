#include "radiosity/rays.hpp"

#include "radiosity/error.hpp"

#include <embree3/rtcore.h>

#include <limits>
#include <mutex>
#include <string>

namespace rad {

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Vec3> normals;
    // Embree reports errors through a callback; the first one is kept and raised after the
    // call that caused it, with Embree's own message.
    std::mutex error_mutex;
    RTCError error = RTC_ERROR_NONE;
    std::string error_message;

    void raise_if_failed(const char* during) {
        std::lock_guard lock(error_mutex);
        if (error == RTC_ERROR_NONE) return;
        const std::string message = std::string("Embree failed while ") + during + ": " +
                                    error_message + " (error " + std::to_string(error) + ")";
        if (error == RTC_ERROR_OUT_OF_MEMORY) throw SystemError(message);
        throw InternalError(message);
    }
};

namespace {
extern "C" void record_embree_error(void* user, RTCError code, const char* message) {
    auto* impl = static_cast<RayScene::Impl*>(user);
    std::lock_guard lock(impl->error_mutex);
    if (impl->error != RTC_ERROR_NONE) return;
    impl->error = code;
    impl->error_message = message ? message : "no message";
}
} // namespace

RayScene::RayScene(const radfmt::MeshData& mesh) : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device)
        throw SystemError("Embree device creation failed (error " +
                          std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceErrorFunction(impl_->device, record_embree_error, impl_.get());
    impl_->scene = rtcNewScene(impl_->device);
    // Robust mode makes shared edges watertight, so rays do not leak between patches.
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);

    // One Embree quad per patch, so a hit's primitive ID is the patch index. Triangles are
    // quads whose last vertex repeats the third (Embree's own encoding).
    const std::size_t count = mesh.patches.size();
    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_QUAD);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), count));
    if (!vertices || !indices) impl_->raise_if_failed("allocating the ray scene's geometry");
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        for (int k = 0; k < 3; ++k) {
            vertices[3 * v + k] = static_cast<float>(mesh.vertices[v][k]);
            lo[k] = std::min(lo[k], mesh.vertices[v][k]);
            hi[k] = std::max(hi[k], mesh.vertices[v][k]);
        }
    for (std::size_t i = 0; i < count; ++i) {
        const auto& p = mesh.patches[i];
        for (int k = 0; k < 4; ++k) indices[4 * i + k] = p.corners[k < p.corner_count() ? k : 2];
        impl_->normals.push_back(p.normal);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(impl_->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(impl_->scene);
    impl_->raise_if_failed("building the ray scene");
    epsilon_ = std::max(1e-9, 1e-5 * length(hi - lo));
}

RayScene::~RayScene() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

bool RayScene::visible(const Vec3& from, const Vec3& to) const {
    const Vec3 d = to - from;
    const double distance = length(d);
    if (distance <= 2 * epsilon_) return true;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = static_cast<float>(from[0]);
    ray.org_y = static_cast<float>(from[1]);
    ray.org_z = static_cast<float>(from[2]);
    ray.dir_x = static_cast<float>(d[0] / distance);
    ray.dir_y = static_cast<float>(d[1] / distance);
    ray.dir_z = static_cast<float>(d[2] / distance);
    ray.tnear = static_cast<float>(epsilon_);
    ray.tfar = static_cast<float>(distance - epsilon_);
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(impl_->scene, &context, &ray);
    return ray.tfar >= 0; // Embree sets tfar to -inf on a hit
}

std::int64_t RayScene::first_hit(const Vec3& origin, const Vec3& direction, bool& front) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = static_cast<float>(origin[0]);
    rh.ray.org_y = static_cast<float>(origin[1]);
    rh.ray.org_z = static_cast<float>(origin[2]);
    rh.ray.dir_x = static_cast<float>(direction[0]);
    rh.ray.dir_y = static_cast<float>(direction[1]);
    rh.ray.dir_z = static_cast<float>(direction[2]);
    rh.ray.tnear = static_cast<float>(epsilon_);
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
    const auto patch = rh.hit.primID;
    front = dot(direction, impl_->normals[patch]) < 0;
    return patch;
}

} // namespace rad
