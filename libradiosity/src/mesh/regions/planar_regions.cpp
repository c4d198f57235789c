// Pass 1 of mesh_surfaces: faces grouped into planar regions.
#include "mesh/geometry/point_buckets.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_map>

namespace rad::surfaces {

FaceSubEdges split_face_edges(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                              const PointBuckets& buckets, double tolerance) {
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

namespace {

// Where a region stops though a coplanar face continues it: along a crease (a contact line),
// or where another surface leaves the plane (a wall welded to the floor between two rooms):
// each side sees its own room.
class RegionBounds {
  public:
    RegionBounds(const radfmt::MeshData& faces, const FacesByEdge& by_edge,
                 std::vector<EdgeKey> creases, double min_cos)
        : faces_(faces), by_edge_(by_edge), creases_(std::move(creases)), min_cos_(min_cos) {}
    bool crease(EdgeKey key) const {
        return std::binary_search(creases_.begin(), creases_.end(), key);
    }
    // Whether faces sharing sub-edge `key` are kept apart in a region of `normal`.
    bool apart(EdgeKey key, const Vec3& normal) const {
        if (crease(key)) return true;
        bool rises = false;
        by_edge_.for_each_face(key, [&](std::uint32_t h) {
            rises = rises || std::abs(dot(normalized(faces_.patches[h].normal), normal)) < min_cos_;
        });
        return rises;
    }

  private:
    const radfmt::MeshData& faces_;
    const FacesByEdge& by_edge_;
    std::vector<EdgeKey> creases_;
    double min_cos_;
};

// Faces no wider than the tolerance (their area over their longest edge): rounding, such as a
// glTF's float sliver beside an edge, not a side of anything.
std::vector<char> rounding_slivers(const radfmt::MeshData& faces, double tolerance) {
    std::vector<char> sliver;
    sliver.reserve(faces.patches.size());
    for (const auto& p : faces.patches)
        sliver.push_back(p.area <= tolerance * longest_edge(faces, p));
    return sliver;
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

namespace {

// Regions grown from seed faces across shared sub-edges (pass 1's walk).
class RegionGrower {
  public:
    RegionGrower(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                 const Points& points, const FaceSubEdges& sub_edges, const FacesByEdge& by_edge,
                 const RegionBounds& bounds, double min_cos, double max_offset)
        : region_of(faces.patches.size(), kNone), faces_(faces), weld_(weld), points_(points),
          sub_edges_(sub_edges), by_edge_(by_edge), bounds_(bounds), min_cos_(min_cos),
          max_offset_(max_offset) {}

    // A region grown from `seed` over the faces `may_join` allows.
    template <class MayJoin> void grow(std::uint32_t seed, MayJoin&& may_join) {
        Region region;
        const auto& s = faces_.patches[seed];
        region.group = s.group;
        region.material = s.material;
        region.plane = plane_of(s);
        const auto id = static_cast<std::uint32_t>(regions.size());
        std::queue<std::uint32_t> todo;
        todo.push(seed);
        region_of[seed] = id;
        while (!todo.empty()) {
            const auto f = todo.front();
            todo.pop();
            region.faces.push_back(f);
            for (auto k = sub_edges_.start[f]; k < sub_edges_.start[f + 1]; ++k) {
                const auto key = sub_edges_.keys[k];
                int apart = -1; // whether the edge bounds the region: asked once a face fits
                by_edge_.for_each_face(key, [&](std::uint32_t g) {
                    if (region_of[g] != kNone || !may_join(g) || !fits(region, g)) return;
                    if (apart < 0) apart = bounds_.apart(key, region.plane.normal);
                    if (apart) return;
                    region_of[g] = id;
                    todo.push(g);
                });
            }
        }
        regions.push_back(std::move(region));
    }

    // Face f joins the first region beside it that it fits, across any sub-edge but a
    // crease, and takes no other face with it (false: none).
    bool attach(std::uint32_t f) {
        for (auto k = sub_edges_.start[f]; k < sub_edges_.start[f + 1]; ++k) {
            if (bounds_.crease(sub_edges_.keys[k])) continue;
            std::uint32_t found = kNone;
            by_edge_.for_each_face(sub_edges_.keys[k], [&](std::uint32_t g) {
                const auto r = region_of[g];
                if (found == kNone && r != kNone && fits(regions[r], f)) found = r;
            });
            if (found != kNone) {
                region_of[f] = found;
                regions[found].faces.push_back(f);
                return true;
            }
        }
        return false;
    }

    std::vector<Region> regions;
    std::vector<std::uint32_t> region_of; // each face's region (kNone: none yet)

  private:
    // Same group and material, normals within the angle, corners within the plane's offset.
    bool fits(const Region& region, std::uint32_t f) const {
        const auto& p = faces_.patches[f];
        if (p.group != region.group || p.material != region.material) return false;
        if (dot(normalized(p.normal), region.plane.normal) < min_cos_) return false;
        for (int k = 0; k < p.corner_count(); ++k)
            if (std::abs(dot(points_.position[weld_[p.corners[k]]] - region.plane.origin,
                             region.plane.normal)) > max_offset_)
                return false;
        return true;
    }

    const radfmt::MeshData& faces_;
    const std::vector<std::uint32_t>& weld_;
    const Points& points_;
    const FaceSubEdges& sub_edges_;
    const FacesByEdge& by_edge_;
    const RegionBounds& bounds_;
    double min_cos_, max_offset_;
};

} // namespace

// The sub-edges lying along the creases (between points that lie on one), sorted.
std::vector<EdgeKey> crease_edges(const std::vector<std::array<Vec3, 2>>& creases,
                                  const PointBuckets& buckets, double tolerance) {
    std::vector<EdgeKey> out;
    for (const auto& [a, b] : creases) {
        const auto on = buckets.along(a, b, tolerance);
        for (std::size_t k = 1; k < on.size(); ++k)
            if (on[k - 1] != on[k]) out.push_back(edge_key(on[k - 1], on[k]));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<Region> find_planar_regions(const radfmt::MeshData& faces,
                                        const std::vector<std::uint32_t>& weld,
                                        const Points& points, const SurfaceOptions& options,
                                        double scene_size, double tolerance) {
    std::vector<std::uint32_t> ids(points.position.size());
    for (std::uint32_t k = 0; k < ids.size(); ++k) ids[k] = k;
    const PointBuckets buckets(ids, points);
    const auto sub_edges = split_face_edges(faces, weld, buckets, tolerance);
    const FacesByEdge by_edge(sub_edges);
    const double min_cos = std::cos(options.angle_tolerance * 3.14159265358979323846 / 180);
    const RegionBounds bounds(faces, by_edge, crease_edges(options.creases, buckets, tolerance),
                              min_cos);
    RegionGrower grower(faces, weld, points, sub_edges, by_edge, bounds, min_cos,
                        options.plane_tolerance * scene_size);
    // Slivers of rounding first left out, then each given to a region beside it: through
    // them a region would reach across a wall's edge it stops at.
    const auto sliver = rounding_slivers(faces, tolerance);
    const auto whole = [&](std::uint32_t g) { return !sliver[g]; };
    for (std::uint32_t f = 0; f < faces.patches.size(); ++f)
        if (!sliver[f] && grower.region_of[f] == kNone) grower.grow(f, whole);
    for (std::uint32_t f = 0; f < faces.patches.size(); ++f)
        if (sliver[f] && grower.region_of[f] == kNone) grower.attach(f);
    const auto any = [](std::uint32_t) { return true; };
    for (std::uint32_t f = 0; f < faces.patches.size(); ++f)
        if (grower.region_of[f] == kNone) grower.grow(f, any);
    return std::move(grower.regions);
}

} // namespace rad::surfaces
