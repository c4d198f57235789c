#include "radiosity/orientation.hpp"

#include "core/union_find.hpp"
#include "mesh/load/weld.hpp"
#include "mesh/orientation/room_box.hpp"
#include "radiosity/error.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/vec.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <numeric>
#include <span>
#include <tuple>
#include <unordered_map>

namespace rad {

namespace {

void add_finding(std::vector<OrientationFinding>& out, OrientationFinding::Kind kind,
                 const Scene& scene, const std::vector<std::size_t>& polygons,
                 const std::vector<bool>& flip) {
    // Faces of the unnamed group go by material: the only name the file gives them.
    std::map<std::pair<std::uint32_t, std::int64_t>, std::vector<std::size_t>> by_name;
    for (auto p : polygons) {
        const auto& polygon = scene.polygons[p];
        const bool unnamed = scene.groups[polygon.group] == "default";
        by_name[{polygon.group, unnamed ? std::int64_t(polygon.material) : -1}].push_back(p);
    }
    for (auto& [name, list] : by_name) {
        std::sort(list.begin(), list.end());
        std::vector<std::size_t> to_flip;
        for (auto p : list)
            if (flip[p]) to_flip.push_back(p);
        OrientationFinding finding;
        finding.kind = kind;
        finding.group = name.first;
        finding.polygons = std::move(list);
        finding.to_flip = std::move(to_flip);
        if (name.second >= 0) finding.material = static_cast<std::uint32_t>(name.second);
        out.push_back(std::move(finding));
    }
}

std::vector<Vec3> points_of(const Scene& scene, const Polygon& p) {
    std::vector<Vec3> pts;
    for (auto v : p.vertices) pts.push_back(scene.vertices[v]);
    return pts;
}

// Faces connected across welded edges (two faces per edge), whatever their winding.
struct SurfaceGraph {
    // Per face: (neighbour, whether the two run along the shared edge the same way, i.e.
    // disagree in winding), face f's from start[f] to start[f + 1].
    struct Neighbours {
        std::vector<std::size_t> start;
        std::vector<std::pair<std::size_t, bool>> list;
        std::span<const std::pair<std::size_t, bool>> operator[](std::size_t f) const {
            return {list.data() + start[f], list.data() + start[f + 1]};
        }
    } neighbours;
    std::vector<bool> open_edge_of; // has an edge used by one face (or more than two)
    std::vector<std::vector<std::size_t>> members; // the connected surfaces, faces ascending
    std::vector<std::size_t> surface_of;           // per face: its surface in members
};

// Each face's edges by their welded ends (sorted by edge, then face), skipping faces without
// area: they have no side to agree on.
struct EdgeUse {
    std::uint64_t edge; // smaller welded id << 32 | larger
    std::uint32_t polygon;
    bool forward; // runs from the smaller welded id to the larger
    bool operator<(const EdgeUse& o) const {
        return std::tie(edge, polygon, forward) < std::tie(o.edge, o.polygon, o.forward);
    }
};
std::vector<EdgeUse> edge_uses(const Scene& scene) {
    const auto id = weld_by_position(scene.vertices);
    std::vector<EdgeUse> uses;
    std::vector<Vec3> pts;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f) {
        const auto& vs = scene.polygons[f].vertices;
        pts.clear();
        for (const auto v : vs) pts.push_back(scene.vertices[v]);
        double size = 0;
        for (const auto& p : pts) size = std::max(size, length(p - pts.front()));
        if (!(length(newell_normal(pts)) > 1e-12 * size * size)) continue;
        for (std::size_t k = 0; k < vs.size(); ++k) {
            const auto a = id[vs[k]], b = id[vs[(k + 1) % vs.size()]];
            if (a == b) continue;
            uses.push_back({(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b),
                            static_cast<std::uint32_t>(f), a < b});
        }
    }
    std::sort(uses.begin(), uses.end());
    return uses;
}

SurfaceGraph connect_surfaces(const Scene& scene) {
    const std::size_t n = scene.polygons.size();
    const auto uses = edge_uses(scene);
    SurfaceGraph graph;
    UnionFind components(n);
    graph.open_edge_of.assign(n, false);
    std::vector<std::array<std::size_t, 2>> pairs; // the two faces of each shared edge
    std::vector<char> same_way;
    for (std::size_t k = 0; k < uses.size();) {
        std::size_t end = k;
        while (end < uses.size() && uses[end].edge == uses[k].edge) ++end;
        if (end - k != 2) {
            for (auto u = k; u < end; ++u) graph.open_edge_of[uses[u].polygon] = true;
        } else if (uses[k].polygon != uses[k + 1].polygon) {
            components.unite(uses[k].polygon, uses[k + 1].polygon);
            pairs.push_back({uses[k].polygon, uses[k + 1].polygon});
            same_way.push_back(uses[k].forward == uses[k + 1].forward);
        }
        k = end;
    }
    auto& nb = graph.neighbours;
    nb.start.assign(n + 1, 0);
    for (const auto& [a, b] : pairs) ++nb.start[a + 1], ++nb.start[b + 1];
    for (std::size_t f = 0; f < n; ++f) nb.start[f + 1] += nb.start[f];
    nb.list.resize(nb.start[n]);
    auto next = nb.start;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const auto [a, b] = pairs[k];
        nb.list[next[a]++] = {b, same_way[k] != 0};
        nb.list[next[b]++] = {a, same_way[k] != 0};
    }
    std::map<std::size_t, std::size_t> index_of_root;
    graph.surface_of.resize(n);
    for (std::size_t f = 0; f < n; ++f) {
        const auto [it, added] =
            index_of_root.try_emplace(components.find(f), graph.members.size());
        if (added) graph.members.emplace_back();
        graph.members[it->second].push_back(f);
        graph.surface_of[f] = it->second;
    }
    return graph;
}

// Each finding's surface_line: the first line of the connected surface of its first face.
void name_surfaces(std::vector<OrientationFinding>& findings, const Scene& scene,
                   const SurfaceGraph& surfaces) {
    for (auto& finding : findings) {
        if (finding.polygons.empty()) continue;
        int first = scene.polygons[finding.polygons.front()].line;
        for (const auto f : surfaces.members[surfaces.surface_of[finding.polygons.front()]])
            first = std::min(first, scene.polygons[f].line);
        finding.surface_line = first;
    }
}

// Each face's geometry, once: Newell normal (length twice the area), centroid, area.
struct FaceGeometry {
    Vec3 normal2, centroid;
    double area;
};

// The faces' geometry, and the box around every face (to tell a room, a surface around all
// the rest, from objects).
std::vector<FaceGeometry> face_geometry(const Scene& scene, Box& scene_box) {
    std::vector<FaceGeometry> face(scene.polygons.size());
    for (std::size_t f = 0; f < face.size(); ++f) {
        const auto pts = points_of(scene, scene.polygons[f]);
        const Vec3 n2 = newell_normal(pts);
        face[f] = {n2, polygon_centroid(pts), 0.5 * length(n2)};
        for (const auto& p : pts) scene_box.add(p);
    }
    return face;
}

std::vector<std::size_t> faces_against_normals(const Scene& scene,
                                               const std::vector<FaceGeometry>& face) {
    std::vector<std::size_t> against;
    for (std::size_t f = 0; f < face.size(); ++f) {
        const auto& p = scene.polygons[f];
        if (length(p.vn_sum) == 0 || p.vertices.size() < 3) continue;
        if (dot(face[f].normal2, p.vn_sum) < 0) against.push_back(f);
    }
    return against;
}

// Breadth-first parity over one connected surface: 1 = flipped relative to its first face.
// False when no parity is consistent (a Moebius-like tangle).
bool winding_parity(const std::vector<std::size_t>& faces, const SurfaceGraph& surfaces,
                    std::vector<int>& parity) {
    bool orientable = true;
    std::deque<std::size_t> queue{faces.front()};
    parity[faces.front()] = 0;
    while (!queue.empty()) {
        const auto f = queue.front();
        queue.pop_front();
        for (const auto& [g, same] : surfaces.neighbours[f]) {
            const int want = parity[f] ^ (same ? 1 : 0);
            if (parity[g] < 0) {
                parity[g] = want;
                queue.push_back(g);
            } else if (parity[g] != want) {
                orientable = false;
            }
        }
    }
    return orientable;
}

// The faces of the surfaces of `faces` that are not to be flipped: flipped instead, they make
// those surfaces just as consistent, the other way round (ascending).
std::vector<std::size_t> rest_of_surfaces(const std::vector<std::size_t>& faces,
                                          const SurfaceGraph& surfaces,
                                          const std::vector<bool>& flip) {
    std::vector<std::size_t> ids;
    for (auto f : faces) ids.push_back(surfaces.surface_of[f]);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<std::size_t> rest;
    for (auto id : ids)
        for (auto f : surfaces.members[id])
            if (!flip[f]) rest.push_back(f);
    std::sort(rest.begin(), rest.end());
    return rest;
}

struct SurfaceVerdict {
    int minority = 1; // the parity class of lesser area
    int right = 0;    // the parity class facing the right way
    bool room = false;
};

// Whether one of the emitting faces `lamps` of another surface has its centroid strictly
// inside `box` (of `faces`, one connected surface, ascending).
bool holds_lamp(const std::vector<std::size_t>& faces, const std::vector<std::size_t>& lamps,
                const std::vector<FaceGeometry>& face, const Box& box) {
    const auto inside = [&](const Vec3& p) {
        for (int c = 0; c < 3; ++c)
            if (!(p[c] > box.lo[c] && p[c] < box.hi[c])) return false;
        return true;
    };
    for (const auto f : lamps)
        if (inside(face[f].centroid) && !std::binary_search(faces.begin(), faces.end(), f))
            return true;
    return false;
}

// Which parity class of a connected surface faces the right way. Facing inward is right for a
// room, a surface that encloses everything else; any other surface is an object, which must
// face outward.
SurfaceVerdict judge_surface(const std::vector<std::size_t>& faces, const Scene& scene,
                             const std::vector<FaceGeometry>& face, const std::vector<int>& parity,
                             const SurfaceGraph& surfaces, const Box& scene_box,
                             const std::vector<std::size_t>& lamps) {
    double area[2] = {0, 0};
    Box box;
    Vec3 centre{0, 0, 0};
    double total_area = 0;
    for (auto f : faces) {
        area[parity[f]] += face[f].area;
        centre = centre + face[f].centroid * face[f].area;
        total_area += face[f].area;
        for (auto v : scene.polygons[f].vertices) box.add(scene.vertices[v]);
    }
    if (total_area > 0) centre = centre * (1 / total_area);
    SurfaceVerdict verdict;
    verdict.minority = area[1] <= area[0] ? 1 : 0;
    const bool closed =
        std::none_of(faces.begin(), faces.end(), [&](auto f) { return surfaces.open_edge_of[f]; });
    // A room encloses everything else, or, drawn facing in, holds a lamp of another surface
    // (two rooms side by side, a house whose roof overhangs its walls: lit inside, not objects
    // inside out; a lamp's housing drawn facing out stays an object).
    double drawn = 0; // < 0: the faces as drawn point towards the centre
    for (auto f : faces) drawn += dot(face[f].normal2, face[f].centroid - centre);
    verdict.room = encloses(box, scene_box) || (drawn < 0 && holds_lamp(faces, lamps, face, box));
    // For an open room or a surface alone in its scene (an empty room or a lone object?), the
    // majority; otherwise the one whose faces point away from the surface's centre (an object)
    // or towards it (a closed room around other things). For a closed surface the score below
    // is six times its signed volume.
    verdict.right = 1 - verdict.minority;
    if (!verdict.room || (closed && faces.size() < scene.polygons.size())) {
        double score = 0; // > 0: parity-0 faces as written point away from the centre
        for (auto f : faces)
            score += (parity[f] == 0 ? 1 : -1) * dot(face[f].normal2, face[f].centroid - centre);
        // A flat or nearly flat surface has no inside: keep its majority. A closed surface
        // must show a volume of at least 1% of its area times its size.
        const double scale = (closed ? 6 : 1) * total_area * length(box.hi - box.lo);
        if (std::abs(score) > 0.01 * scale) verdict.right = (score > 0) == !verdict.room ? 0 : 1;
    }
    return verdict;
}

} // namespace

std::vector<OrientationFinding> check_orientation(const Scene& scene) {
    std::vector<OrientationFinding> findings;
    const std::size_t n = scene.polygons.size();
    Box scene_box;
    const auto face = face_geometry(scene, scene_box);

    // 1. Faces wound against their own vn normals (vn may be the wrong part: report, never fix).
    add_finding(findings, OrientationFinding::Kind::AgainstNormals, scene,
                faces_against_normals(scene, face), std::vector<bool>(n, false));

    // 2. Connected surfaces over welded edges, and each face's winding relative to its
    // neighbours: two faces agree when they run along their shared edge in opposite
    // directions. The minority (by area) disagrees with the rest.
    const auto surfaces = connect_surfaces(scene);
    std::vector<std::size_t> lamps; // the emitting faces, which tell a room (lit inside)
    for (std::size_t f = 0; f < n; ++f)
        if (scene.materials[scene.polygons[f].material].emits()) lamps.push_back(f);
    std::vector<std::size_t> against_neighbours, inside_out, room_outward;
    std::vector<bool> flip(n, false);
    std::vector<int> parity(n, -1);
    for (const auto& faces : surfaces.members) {
        if (faces.size() < 2 || !winding_parity(faces, surfaces, parity)) continue;
        const auto verdict = judge_surface(faces, scene, face, parity, surfaces, scene_box, lamps);
        for (auto f : faces) {
            if (parity[f] == verdict.right) continue;
            flip[f] = true;
            (parity[f] == verdict.minority ? against_neighbours
             : verdict.room                ? room_outward
                                           : inside_out)
                .push_back(f);
        }
    }
    add_finding(findings, OrientationFinding::Kind::AgainstNeighbours, scene, against_neighbours,
                flip);
    for (auto& finding : findings)
        if (finding.kind == OrientationFinding::Kind::AgainstNeighbours)
            finding.instead = rest_of_surfaces(finding.to_flip, surfaces, flip);
    add_finding(findings, OrientationFinding::Kind::InsideOut, scene, inside_out, flip);
    add_finding(findings, OrientationFinding::Kind::RoomOutward, scene, room_outward, flip);
    name_surfaces(findings, scene, surfaces);
    return findings;
}

radfmt::MeshData face_triangles(const Scene& scene, std::vector<std::size_t>* face_of,
                                std::vector<double>* triangle_area,
                                const std::vector<bool>* reversed) {
    radfmt::MeshData mesh;
    mesh.vertices = scene.vertices;
    std::size_t triangles = 0;
    for (const auto& polygon : scene.polygons)
        triangles += polygon.vertices.size() >= 3 ? polygon.vertices.size() - 2 : 0;
    mesh.patches.reserve(triangles);
    if (face_of) face_of->reserve(triangles);
    if (triangle_area) triangle_area->reserve(triangles);
    std::vector<Vec3> pts;
    std::vector<std::uint32_t> vs;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f) {
        vs = scene.polygons[f].vertices;
        if (reversed && f < reversed->size() && (*reversed)[f]) std::reverse(vs.begin(), vs.end());
        pts.clear();
        for (const auto v : vs) pts.push_back(scene.vertices[v]);
        const Vec3 n2 = newell_normal(pts);
        if (vs.size() < 3 || length(n2) == 0) continue;
        for (std::size_t k = 1; k + 1 < vs.size(); ++k) {
            radfmt::Patch t;
            t.corners = {vs[0], vs[k], vs[k + 1], radfmt::kNoVertex};
            t.normal = normalized(n2);
            mesh.patches.push_back(t);
            if (face_of) face_of->push_back(f);
            if (triangle_area)
                triangle_area->push_back(0.5 * length(cross(pts[k] - pts[0], pts[k + 1] - pts[0])));
        }
    }
    return mesh;
}

namespace {

// What the rays from one side of a surface met: hits on the front or back of each other
// surface, and escapes.
struct SideTally {
    struct Link {
        std::size_t target;
        int facing; // 0: met the target's front, 1: its back (as the faces are now)
        double rays;
    };
    std::vector<Link> links;
    double escaped = 0;
};

struct SurfaceTally {
    std::array<SideTally, 2> sides; // front, back
    double rays_per_side = 0;
    bool free = false; // may be flipped (not a closed object)
};

// The triangles of the scene's faces, for the ray casts, and each surface's triangles.
struct TracedSurfaces {
    std::vector<std::size_t> face_of;                   // per triangle
    std::vector<double> triangle_area;                  // per triangle
    std::vector<std::vector<std::size_t>> triangles_of; // per surface
    radfmt::MeshData mesh;
};

TracedSurfaces traced_surfaces(const Scene& scene, const SurfaceGraph& surfaces) {
    TracedSurfaces traced;
    traced.mesh = face_triangles(scene, &traced.face_of, &traced.triangle_area);
    traced.triangles_of.resize(surfaces.members.size());
    for (std::size_t t = 0; t < traced.face_of.size(); ++t)
        traced.triangles_of[surfaces.surface_of[traced.face_of[t]]].push_back(t);
    return traced;
}

// Cosine-weighted rays from both sides of surface c (a few per face, at least 64 and at most
// 1024 per side), from area-uniform points of its triangles.
SurfaceTally tally_surface(std::size_t c, const Scene& scene, const SurfaceGraph& surfaces,
                           const TracedSurfaces& traced, const RayScene& rays) {
    SurfaceTally tally;
    const auto& faces = surfaces.members[c];
    const auto& triangles = traced.triangles_of[c];
    if (triangles.empty()) return tally;
    std::vector<double> cdf;
    double total = 0;
    for (auto t : triangles) cdf.push_back(total += traced.triangle_area[t]);
    if (!(total > 0)) return tally;
    // Closed surfaces stay as their volume says, but cast rays too: others see them.
    tally.free =
        std::any_of(faces.begin(), faces.end(), [&](auto f) { return surfaces.open_edge_of[f]; });
    const int count = static_cast<int>(std::clamp<std::size_t>(64 * faces.size(), 64, 1024));
    tally.rays_per_side = count;
    Rng rng(0x0F1A, c);
    for (int side = 0; side < 2; ++side) {
        std::map<std::pair<std::size_t, int>, double> met;
        for (int r = 0; r < count; ++r) {
            const double pick = rng.uniform() * total;
            const auto t = triangles[std::min<std::size_t>(
                std::lower_bound(cdf.begin(), cdf.end(), pick) - cdf.begin(),
                triangles.size() - 1)];
            const auto& tri = traced.mesh.patches[t];
            const Vec3 a = scene.vertices[tri.corners[0]], b = scene.vertices[tri.corners[1]],
                       d = scene.vertices[tri.corners[2]];
            double u = rng.uniform(), v = rng.uniform();
            if (u + v > 1) u = 1 - u, v = 1 - v;
            const Vec3 origin = a + (b - a) * u + (d - a) * v;
            const Vec3 normal = side == 0 ? tri.normal : tri.normal * -1.0;
            const Vec3 tu = orthogonal(normal), tv = cross(normal, tu);
            const double u2 = rng.uniform(), u3 = rng.uniform();
            const Vec3 dir = cosine_direction(normal, tu, tv, u2, u3);
            bool front = false;
            const auto hit = rays.first_hit(origin, dir, front);
            if (hit < 0) {
                tally.sides[side].escaped += 1;
            } else if (const auto target = surfaces.surface_of[traced.face_of[hit]]; target != c) {
                met[{target, front ? 0 : 1}] += 1; // its own surface turns with it
            }
        }
        for (const auto& [key, rays_met] : met)
            tally.sides[side].links.push_back({key.first, key.second, rays_met});
    }
    return tally;
}

// How well side `t` (0 front, 1 back, after the flips so far) of surface c faces what it sees:
// +1 per ray that meets a front, -1 per ray that meets a back or escapes. A surface faces the
// wrong way when its back does clearly better than its front. The evidence is mutual (a room
// split into separately modelled walls: each sees the others' backs until one turns), so the
// clearest case is flipped first, then the rest is weighed again.
class FacingVote {
  public:
    explicit FacingVote(const std::vector<SurfaceTally>& tally)
        : tally_(tally), flipped_(tally.size(), 0), advantage_(tally.size(), 0),
          seen_by_(tally.size()) {
        for (std::size_t c = 0; c < tally.size(); ++c)
            for (int t = 0; t < 2; ++t)
                for (const auto& link : tally[c].sides[t].links) seen_by_[link.target].push_back(c);
        for (auto& list : seen_by_) {
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
        }
        for (std::size_t c = 0; c < tally.size(); ++c) weigh(c);
    }
    // The surfaces to flip (1), clearest first, until none is clearly better turned.
    std::vector<int> vote() {
        constexpr double kClearly = 0.2; // a fifth of the rays, net
        for (std::size_t step = 0; step < 2 * tally_.size() + 2; ++step) {
            const auto best =
                std::max_element(advantage_.begin(), advantage_.end()) - advantage_.begin();
            if (advantage_[best] <= kClearly) break;
            flipped_[best] ^= 1;
            weigh(best);
            for (auto c : seen_by_[best]) weigh(c);
        }
        return flipped_;
    }

  private:
    double quality(std::size_t c, int t) const {
        const auto& side = tally_[c].sides[t ^ flipped_[c]];
        double sum = -side.escaped;
        for (const auto& link : side.links)
            sum += ((link.facing ^ flipped_[link.target]) == 0 ? 1 : -1) * link.rays;
        return sum / std::max(1.0, tally_[c].rays_per_side);
    }
    // A surface is a candidate when its front does badly (meets mostly backs, or nothing) and
    // its back clearly better; a lamp under a ceiling, whose back sees the ceiling's front, is
    // not one: its front sees the room.
    void weigh(std::size_t c) {
        const double front = quality(c, 0);
        advantage_[c] = tally_[c].free && front < 0 ? quality(c, 1) - front : 0;
    }

    const std::vector<SurfaceTally>& tally_;
    std::vector<int> flipped_;
    std::vector<double> advantage_;
    std::vector<std::vector<std::size_t>> seen_by_;
};

} // namespace

std::vector<OrientationFinding> check_facing_by_visibility(const Scene& scene) {
    const auto surfaces = connect_surfaces(scene);
    const auto traced = traced_surfaces(scene, surfaces);
    if (traced.mesh.patches.empty()) return {};
    const RayScene rays(traced.mesh, RayBuild::Fast);
    std::vector<SurfaceTally> tally(surfaces.members.size());
    tbb::parallel_for(std::size_t(0), tally.size(), [&](std::size_t c) {
        tally[c] = tally_surface(c, scene, surfaces, traced, rays);
    });
    const auto flipped = FacingVote(tally).vote();
    std::vector<std::size_t> facing_away;
    std::vector<bool> flip(scene.polygons.size(), false);
    for (std::size_t c = 0; c < flipped.size(); ++c)
        if (flipped[c])
            for (auto f : surfaces.members[c]) {
                facing_away.push_back(f);
                flip[f] = true;
            }
    std::sort(facing_away.begin(), facing_away.end());
    std::vector<OrientationFinding> findings;
    add_finding(findings, OrientationFinding::Kind::FacingAway, scene, facing_away, flip);
    name_surfaces(findings, scene, surfaces);
    return findings;
}

std::string describe(const OrientationFinding& finding, const Scene& scene) {
    const char* what = "";
    switch (finding.kind) {
    case OrientationFinding::Kind::AgainstNormals:
        what = "wound against their own vn normals";
        break;
    case OrientationFinding::Kind::AgainstNeighbours:
        what = "wound against their neighbours across shared edges";
        break;
    case OrientationFinding::Kind::InsideOut:
        what = "face into their object (inside out)";
        break;
    case OrientationFinding::Kind::RoomOutward:
        what = "face out of their room (a closed surface around the rest of the scene must "
               "face in)";
        break;
    case OrientationFinding::Kind::FacingAway:
        what = "face away from what they see (their back sees the front of other surfaces, "
               "their front does not)";
        break;
    }
    const auto& first = scene.polygons[finding.polygons.front()];
    const std::string whose = finding.material
                                  ? "material " + scene.materials[*finding.material].name +
                                        ", the connected surface from " +
                                        face_location(scene, finding.surface_line)
                                  : "group " + scene.groups[finding.group];
    return whose + ": " + std::to_string(finding.polygons.size()) + " face(s) " + what +
           " (first at " + face_location(scene, first.line) + ")";
}

namespace {
// The face a --flip name points at as a place: "LINE" or "FILE:LINE" (FILE as messages print
// it, or its file name), the line of its 'f' statement; -1 when it is not such a name.
long named_face(const Scene& scene, const std::string& name) {
    const auto colon = name.rfind(':');
    const std::string digits = colon == std::string::npos ? name : name.substr(colon + 1);
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return -1;
    if (colon != std::string::npos) {
        const auto file = name.substr(0, colon);
        if (file != scene.path && file != std::filesystem::path(scene.path).filename().string())
            return -1;
    }
    const long line = std::stol(digits);
    for (std::size_t f = 0; f < scene.polygons.size(); ++f)
        if (scene.polygons[f].line == line) return static_cast<long>(f);
    throw InputError("--flip " + name + ": no face of " + scene.path + " is on line " + digits +
                     " (name a face's 'f' line, as rad-mesh's messages do)");
}
} // namespace

std::vector<FlipResult> flip_groups(Scene& scene, const std::vector<std::string>& names) {
    std::vector<FlipResult> out;
    for (const auto& name : names) {
        // A face's place: its connected surface, when names cannot separate it (a vault
        // sharing its material with the floor, in a file without groups).
        if (std::find(scene.groups.begin(), scene.groups.end(), name) == scene.groups.end())
            if (const long face = named_face(scene, name); face >= 0) {
                const auto surfaces = connect_surfaces(scene);
                FlipResult result{name, "connected surface", 0};
                for (const auto f : surfaces.members[surfaces.surface_of[std::size_t(face)]]) {
                    std::reverse(scene.polygons[f].vertices.begin(),
                                 scene.polygons[f].vertices.end());
                    ++result.faces;
                }
                out.push_back(result);
                continue;
            }
        // A group (or object) by that name, else a material: a file without groups (one
        // 'default') still names its lamp's material.
        const auto group = std::find(scene.groups.begin(), scene.groups.end(), name);
        const auto material =
            std::find_if(scene.materials.begin(), scene.materials.end(),
                         [&](const radfmt::Material& m) { return m.name == name; });
        const bool by_group = group != scene.groups.end();
        if (!by_group && material == scene.materials.end()) {
            std::string groups, materials;
            for (const auto& g : scene.groups) groups += (groups.empty() ? "" : ", ") + g;
            for (const auto& m : scene.materials)
                materials += (materials.empty() ? "" : ", ") + m.name;
            throw InputError("--flip: no group '" + name + "' and no material of that name in " +
                             scene.path + " (groups: " + groups + "; materials: " + materials +
                             "; or a face as FILE:LINE, for its connected surface)");
        }
        const auto index = static_cast<std::uint32_t>(
            by_group ? group - scene.groups.begin() : material - scene.materials.begin());
        FlipResult result{name, by_group ? "group" : "material", 0};
        for (auto& p : scene.polygons)
            if ((by_group ? p.group : p.material) == index) {
                std::reverse(p.vertices.begin(), p.vertices.end());
                ++result.faces;
            }
        out.push_back(result);
    }
    return out;
}

std::vector<std::pair<std::string, std::size_t>>
fix_orientation(Scene& scene, const std::vector<OrientationFinding>& findings) {
    std::map<std::string, std::size_t> flipped;
    std::vector<bool> flip(scene.polygons.size(), false);
    for (const auto& finding : findings)
        for (auto p : finding.to_flip) flip[p] = true;
    for (std::size_t p = 0; p < flip.size(); ++p)
        if (flip[p]) {
            std::reverse(scene.polygons[p].vertices.begin(), scene.polygons[p].vertices.end());
            ++flipped[scene.groups[scene.polygons[p].group]];
        }
    return {flipped.begin(), flipped.end()};
}

} // namespace rad
