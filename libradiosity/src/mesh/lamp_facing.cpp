// turn_lamps_facing_backs: an emitter drawn facing into its fixture (the dining room's lamp
// faced up into its shade: 82% of its light landed on the backs of the shade's faces) is
// turned when its other side's light would meet the front of surfaces.
#include "radiosity/orientation.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"

#include <algorithm>

namespace rad {

namespace {
constexpr int kRays = 64; // per triangle of an emitter, from each side

struct SideTally {
    double hits = 0, backs = 0; // area-weighted
    double back_share() const { return hits > 0 ? backs / hits : 0; }
};

// From each side of one triangle: the rays that meet a surface, and those that meet a back.
// Glass (`passes`, per triangle) lets the light on: meeting its back is no fixture.
void tally_triangle(const radfmt::MeshData& mesh, std::size_t t, double area, const RayScene& rays,
                    const std::vector<bool>& passes, SideTally& front, SideTally& back) {
    const auto& p = mesh.patches[t];
    const Vec3 centroid =
        (mesh.vertices[p.corners[0]] + mesh.vertices[p.corners[1]] + mesh.vertices[p.corners[2]]) *
        (1.0 / 3);
    for (const double side : {1.0, -1.0}) {
        const Vec3 n = normalized(p.normal) * side, u = orthogonal(n), v = cross(n, u);
        const Vec3 from = centroid + n * (4 * rays.epsilon());
        Rng rng(0x6c616d70, 2 * t + (side > 0 ? 0 : 1));
        auto& tally = side > 0 ? front : back;
        for (int k = 0; k < kRays; ++k) {
            bool met_front = false;
            const auto hit = rays.first_hit(
                from, cosine_direction(n, u, v, rng.uniform(), rng.uniform()), met_front);
            if (hit < 0 || passes[static_cast<std::size_t>(hit)]) continue;
            tally.hits += area;
            if (!met_front) tally.backs += area;
        }
    }
}
} // namespace

std::vector<LampTurn> turn_lamps_facing_backs(Scene& scene, const std::vector<std::string>& keep) {
    std::vector<std::size_t> face_of;
    std::vector<double> area;
    const auto mesh = face_triangles(scene, &face_of, &area);
    if (mesh.patches.empty()) return {};
    const RayScene rays(mesh, RayBuild::Fast);
    std::vector<bool> passes(mesh.patches.size());
    for (std::size_t t = 0; t < mesh.patches.size(); ++t) {
        passes[t] = scene.materials[scene.polygons[face_of[t]].material].specular.transmits();
    }
    std::vector<SideTally> front(scene.materials.size()), back(scene.materials.size());
    for (std::size_t t = 0; t < mesh.patches.size(); ++t) {
        const auto& polygon = scene.polygons[face_of[t]];
        if (!scene.materials[polygon.material].emits()) continue;
        tally_triangle(mesh, t, area[t], rays, passes, front[polygon.material],
                       back[polygon.material]);
    }
    std::vector<LampTurn> turned;
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const auto& name = scene.materials[m].name;
        // Most of its light on backs, and turned, little: its fixture is in front of it.
        if (!(front[m].back_share() > kLampBackShare) ||
            !(back[m].back_share() < 0.5 * front[m].back_share()))
            continue;
        if (std::find(keep.begin(), keep.end(), name) != keep.end()) continue;
        LampTurn turn{name, 0, front[m].back_share(), back[m].back_share()};
        for (auto& p : scene.polygons)
            if (p.material == m && !std::count(keep.begin(), keep.end(), scene.groups[p.group])) {
                std::reverse(p.vertices.begin(), p.vertices.end());
                ++turn.faces;
            }
        if (turn.faces > 0) turned.push_back(turn);
    }
    return turned;
}

} // namespace rad
