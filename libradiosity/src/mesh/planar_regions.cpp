// Pass 1 of mesh_surfaces: faces grouped into planar regions.
#include "point_buckets.hpp"
#include "regions.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_map>

namespace rad::surfaces {

namespace {

// Each face's welded edges split where another point lies on them (a neighbour's corner partway
// along the edge: a T-junction), as sub-edges keyed by their ends, in CSR form: faces that
// share a sub-edge touch along it, whether or not their corners meet there.
struct FaceSubEdges {
    // faces + 1 entries: face f's sub-edges are keys[start[f] .. start[f + 1]).
    std::vector<std::size_t> start;
    std::vector<EdgeKey> keys;
};

FaceSubEdges split_face_edges(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                              const Points& points, double tolerance) {
    std::vector<std::uint32_t> ids(points.position.size());
    for (std::uint32_t k = 0; k < ids.size(); ++k) ids[k] = k;
    const PointBuckets buckets(ids, points);
    // Each welded edge once (sorted keys, not a map of vectors: a hall of 5e6 triangles has
    // 7.5 million edges), its sub-edges in a flat list, in the direction of the first face
    // that has it.
    struct FaceEdge {
        EdgeKey key;
        std::uint32_t face, from, to;
        bool operator<(const FaceEdge& o) const {
            return std::pair(key, face) < std::pair(o.key, o.face);
        }
    };
    std::vector<FaceEdge> found;
    for (std::uint32_t f = 0; f < faces.patches.size(); ++f) {
        const auto& p = faces.patches[f];
        for (int k = 0, n = p.corner_count(); k < n; ++k) {
            const auto a = weld[p.corners[k]], b = weld[p.corners[(k + 1) % n]];
            if (a != b) found.push_back({edge_key(a, b), f, a, b});
        }
    }
    std::stable_sort(found.begin(), found.end());
    std::vector<EdgeKey> edges;
    std::vector<std::size_t> first{0}; // edge e's sub-edges: first[e] .. first[e + 1]
    std::vector<EdgeKey> sub_edges;
    for (std::size_t i = 0; i < found.size(); ++i) {
        if (i > 0 && found[i].key == found[i - 1].key) continue;
        edges.push_back(found[i].key);
        const auto a = found[i].from, b = found[i].to;
        auto previous = a;
        for (const auto c : buckets.on_segment(a, b, tolerance))
            sub_edges.push_back(edge_key(previous, c)), previous = c;
        sub_edges.push_back(edge_key(previous, b));
        first.push_back(sub_edges.size());
    }
    std::vector<FaceEdge>().swap(found);
    FaceSubEdges out;
    out.start.reserve(faces.patches.size() + 1);
    out.start.push_back(0);
    for (const auto& p : faces.patches) {
        const int n = p.corner_count();
        for (int k = 0; k < n; ++k) {
            const auto a = weld[p.corners[k]], b = weld[p.corners[(k + 1) % n]];
            if (a == b) continue;
            const auto e = static_cast<std::size_t>(
                std::lower_bound(edges.begin(), edges.end(), edge_key(a, b)) - edges.begin());
            out.keys.insert(out.keys.end(), sub_edges.begin() + static_cast<long>(first[e]),
                            sub_edges.begin() + static_cast<long>(first[e + 1]));
        }
        out.start.push_back(out.keys.size());
    }
    return out;
}

// Faces along each sub-edge: (sub-edge, face) sorted, so a sub-edge's faces are a run in
// ascending order. (A map of a vector a sub-edge made 15 million small vectors on a hall of
// 5e6 triangles.)
class FacesByEdge {
  public:
    explicit FacesByEdge(const FaceSubEdges& edges) {
        entries_.reserve(edges.keys.size());
        for (std::uint32_t f = 0; f + 1 < edges.start.size(); ++f)
            for (auto k = edges.start[f]; k < edges.start[f + 1]; ++k)
                entries_.emplace_back(edges.keys[k], f);
        std::sort(entries_.begin(), entries_.end());
        entries_.erase(std::unique(entries_.begin(), entries_.end()), entries_.end());
    }
    template <class Visit> void for_each_face(EdgeKey key, Visit&& visit) const {
        auto it = std::lower_bound(entries_.begin(), entries_.end(), std::pair{key, 0u});
        for (; it != entries_.end() && it->first == key; ++it) visit(it->second);
    }

  private:
    std::vector<std::pair<EdgeKey, std::uint32_t>> entries_;
};

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
                                        double scene_size, double tolerance) {
    const auto sub_edges = split_face_edges(faces, weld, points, tolerance);
    const FacesByEdge by_edge(sub_edges);
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
            for (auto k = sub_edges.start[f]; k < sub_edges.start[f + 1]; ++k)
                by_edge.for_each_face(sub_edges.keys[k], [&](std::uint32_t g) {
                    if (region_of[g] == kNone && joins(faces.patches[g])) {
                        region_of[g] = id;
                        todo.push(g);
                    }
                });
        }
        regions.push_back(std::move(region));
    }
    return regions;
}

} // namespace rad::surfaces
