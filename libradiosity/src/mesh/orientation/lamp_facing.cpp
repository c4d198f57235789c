// turn_lamps_facing_backs: an emitter drawn facing into its fixture (the dining room's lamp
// faced up into its shade: 82% of its light landed on the backs of the shade's faces) is
// turned when its other side's light would meet the front of surfaces; piece by piece, as one
// material's lamps need not all be drawn alike.
#include "radiosity/orientation.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"

#include "core/union_find.hpp"
#include "mesh/load/weld.hpp"

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
// The emitting faces in pieces that touch (share a corner, welded by position), each of one
// material: one lamp of a material can face into its shade while another faces the room.
std::vector<std::vector<std::size_t>> lamp_pieces(const Scene& scene) {
    const auto weld = weld_by_position(scene.vertices);
    std::vector<std::size_t> lamps;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f)
        if (scene.materials[scene.polygons[f].material].emits()) lamps.push_back(f);
    // Keyed by material and corner: lamps of two materials that touch are two pieces.
    auto split = groups_sharing_keys(lamps.size(), [&](std::size_t k, auto add) {
        const auto& polygon = scene.polygons[lamps[k]];
        for (const auto v : polygon.vertices) add(std::uint64_t(polygon.material) << 32 | weld[v]);
    });
    for (auto& piece : split)
        for (auto& k : piece) k = lamps[k];
    return split;
}

// Whether these faces were turned by hand (rad-mesh --flip names their group or material).
bool kept_by_user(const Scene& scene, std::size_t face, const std::vector<std::string>& keep) {
    const auto& polygon = scene.polygons[face];
    return std::count(keep.begin(), keep.end(), scene.materials[polygon.material].name) ||
           std::count(keep.begin(), keep.end(), scene.groups[polygon.group]);
}
} // namespace

std::vector<LampTurn> turn_lamps_facing_backs(Scene& scene, const std::vector<std::string>& keep) {
    std::vector<std::size_t> face_of;
    std::vector<double> area;
    const auto mesh = face_triangles(scene, &face_of, &area);
    if (mesh.patches.empty()) return {};
    const RayScene rays(mesh, RayBuild::Fast);
    std::vector<bool> passes(mesh.patches.size());
    std::vector<std::vector<std::size_t>> triangles_of(scene.polygons.size());
    for (std::size_t t = 0; t < mesh.patches.size(); ++t) {
        passes[t] = scene.materials[scene.polygons[face_of[t]].material].specular.transmits();
        triangles_of[face_of[t]].push_back(t);
    }
    std::vector<LampTurn> turned;
    for (const auto& piece : lamp_pieces(scene)) {
        SideTally front, back;
        for (const auto f : piece)
            for (const auto t : triangles_of[f])
                tally_triangle(mesh, t, area[t], rays, passes, front, back);
        LampTurn turn{scene.materials[scene.polygons[piece.front()].material].name, piece.size(),
                      front.back_share(), back.back_share(), scene.polygons[piece.front()].line};
        // Most of its light on backs, and turned, little: its fixture is in front of it.
        turn.kept = kept_by_user(scene, piece.front(), keep);
        turn.turned = !turn.kept && turn.backs_before > kLampBackShare &&
                      turn.backs_after < 0.5 * turn.backs_before;
        if (turn.turned)
            for (const auto f : piece) {
                auto& vertices = scene.polygons[f].vertices;
                std::reverse(vertices.begin(), vertices.end());
            }
        turned.push_back(turn);
    }
    return turned;
}

} // namespace rad
