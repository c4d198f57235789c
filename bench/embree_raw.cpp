// The limit rad-ff's hemisphere method is measured against: plain Embree 3 casting the same
// kind of rays (cosine-weighted hemisphere, closest hit) from every patch of a mesh, on all
// cores with TBB, with no form-factor bookkeeping.
//   bench-embree-raw MESH RAYS_PER_PATCH   -> prints "rays N seconds S rays_per_second R"
#include "radfmt/kinds.hpp"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: bench-embree-raw MESH RAYS_PER_PATCH\n");
        return 1;
    }
    const auto mesh = radfmt::read_mesh(argv[1]);
    if (mesh.polygon_count() > 0) { // the baseline is one Embree quad a patch
        std::fprintf(stderr,
                     "bench-embree-raw: %s has polygon patches; give it a mesh of "
                     "triangles and quads (the bench's boxes)\n",
                     argv[1]);
        return 1;
    }
    const long rays_per_patch = std::atol(argv[2]);

    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    // One quad per patch (triangles repeat their third vertex): Embree's fastest layout here.
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                           RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                           mesh.vertices.size()));
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                4 * sizeof(unsigned), mesh.patches.size()));
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        for (int k = 0; k < 3; ++k) vb[3 * v + k] = static_cast<float>(mesh.vertices[v][k]);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& p = mesh.patches[i];
        for (int k = 0; k < 4; ++k) ib[4 * i + k] = p.corners[k < p.corner_count() ? k : 2];
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);

    std::atomic<unsigned long long> hits{0};
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(std::size_t(0), mesh.patches.size(), [&](std::size_t i) {
        const auto& p = mesh.patches[i];
        const auto& n = p.normal;
        // An orthonormal frame around the normal.
        double tx[3] = {0, 0, 0};
        if (std::abs(n[0]) > 0.5)
            tx[1] = 1;
        else
            tx[0] = 1;
        double u[3] = {n[1] * tx[2] - n[2] * tx[1], n[2] * tx[0] - n[0] * tx[2],
                       n[0] * tx[1] - n[1] * tx[0]};
        const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (double& c : u) c /= ul;
        const double v[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2],
                             n[0] * u[1] - n[1] * u[0]};
        std::uint64_t state = 0x9E3779B97F4A7C15ull * (i + 1);
        auto uniform = [&] {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            return double(state >> 11) * 0x1.0p-53;
        };
        const auto& a = mesh.vertices[p.corners[0]];
        const auto& b = mesh.vertices[p.corners[1]];
        const auto& c = mesh.vertices[p.corners[2]];
        unsigned long long local = 0;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (long r = 0; r < rays_per_patch; ++r) {
            const double s = std::sqrt(uniform()), w = uniform();
            const double e1 = uniform(), phi = 2 * M_PI * uniform(), radius = std::sqrt(e1);
            const double lx = radius * std::cos(phi), ly = radius * std::sin(phi),
                         lz = std::sqrt(1 - e1);
            RTCRayHit rh{};
            rh.ray.org_x = float(a[0] * (1 - s) + b[0] * s * (1 - w) + c[0] * s * w);
            rh.ray.org_y = float(a[1] * (1 - s) + b[1] * s * (1 - w) + c[1] * s * w);
            rh.ray.org_z = float(a[2] * (1 - s) + b[2] * s * (1 - w) + c[2] * s * w);
            rh.ray.dir_x = float(u[0] * lx + v[0] * ly + n[0] * lz);
            rh.ray.dir_y = float(u[1] * lx + v[1] * ly + n[1] * lz);
            rh.ray.dir_z = float(u[2] * lx + v[2] * ly + n[2] * lz);
            rh.ray.tnear = 1e-5f;
            rh.ray.tfar = INFINITY;
            rh.ray.mask = 0xFFFFFFFFu;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        hits += local;
    });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double rays = double(rays_per_patch) * double(mesh.patches.size());
    std::printf("rays %.0f hits %llu seconds %.4f rays_per_second %.6g\n", rays, hits.load(),
                seconds, rays / seconds);
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}
