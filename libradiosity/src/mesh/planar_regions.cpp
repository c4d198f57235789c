// Pass 1 of mesh_surfaces: faces grouped into planar regions.
#include "regions.hpp"

#include <cmath>
#include <queue>
#include <unordered_map>

namespace rad::surfaces {

namespace {

// Faces around each welded edge.
std::unordered_map<EdgeKey, std::vector<std::uint32_t>>
faces_by_edge(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld) {
    std::unordered_map<EdgeKey, std::vector<std::uint32_t>> by_edge;
    for (std::uint32_t f = 0; f < faces.patches.size(); ++f) {
        const auto& p = faces.patches[f];
        const int n = p.corner_count();
        for (int k = 0; k < n; ++k) {
            const auto a = weld[p.corners[k]], b = weld[p.corners[(k + 1) % n]];
            if (a != b) by_edge[edge_key(a, b)].push_back(f);
        }
    }
    return by_edge;
}

Plane plane_of(const radfmt::Patch& seed) {
    Plane plane;
    plane.normal = normalized(seed.normal);
    plane.origin = seed.centroid;
    plane.u = orthogonal(plane.normal);
    plane.v = cross(plane.normal, plane.u);
    return plane;
}

} // namespace

std::vector<Region> find_planar_regions(const radfmt::MeshData& faces,
                                        const std::vector<std::uint32_t>& weld,
                                        const Points& points, const SurfaceOptions& options,
                                        double scene_size) {
    const auto by_edge = faces_by_edge(faces, weld);
    const double min_cos = std::cos(options.angle_tolerance * 3.14159265358979323846 / 180);
    const double max_offset = options.plane_tolerance * scene_size;
    std::vector<std::uint32_t> region_of(faces.patches.size(), kNone);
    std::vector<Region> regions;
    for (std::uint32_t seed = 0; seed < faces.patches.size(); ++seed) {
        if (region_of[seed] != kNone) continue;
        Region region;
        const auto& s = faces.patches[seed];
        region.group = s.group;
        region.material = s.material;
        region.plane = plane_of(s);
        const auto id = static_cast<std::uint32_t>(regions.size());
        const auto joins = [&](const radfmt::Patch& p) {
            if (p.group != s.group || p.material != s.material) return false;
            if (dot(normalized(p.normal), region.plane.normal) < min_cos) return false;
            for (int k = 0; k < p.corner_count(); ++k)
                if (std::abs(dot(points.position[weld[p.corners[k]]] - region.plane.origin,
                                 region.plane.normal)) > max_offset)
                    return false;
            return true;
        };
        std::queue<std::uint32_t> todo;
        todo.push(seed);
        region_of[seed] = id;
        while (!todo.empty()) {
            const auto f = todo.front();
            todo.pop();
            region.faces.push_back(f);
            const auto& p = faces.patches[f];
            const int n = p.corner_count();
            for (int k = 0; k < n; ++k) {
                const auto a = weld[p.corners[k]], b = weld[p.corners[(k + 1) % n]];
                if (a == b) continue;
                for (const auto g : by_edge.at(edge_key(a, b)))
                    if (region_of[g] == kNone && joins(faces.patches[g])) {
                        region_of[g] = id;
                        todo.push(g);
                    }
            }
        }
        regions.push_back(std::move(region));
    }
    return regions;
}

} // namespace rad::surfaces
