#include "radiosity/orientation.hpp"

#include "radiosity/error.hpp"
#include "radiosity/vec.hpp"
#include "union_find.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <numeric>
#include <unordered_map>

namespace rad {

namespace {

// Vertices welded by position (to a grid far finer than any sensible feature), so faces
// that were written with their own copies of shared corners still connect.
std::vector<std::uint32_t> weld(const Scene& scene) {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto& v : scene.vertices)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
    const double cell = std::max(1e-300, 1e-9 * length(hi - lo));
    std::map<std::array<long long, 3>, std::uint32_t> ids;
    std::vector<std::uint32_t> out(scene.vertices.size());
    for (std::size_t i = 0; i < scene.vertices.size(); ++i) {
        std::array<long long, 3> key;
        for (int k = 0; k < 3; ++k) key[k] = std::llround((scene.vertices[i][k] - lo[k]) / cell);
        out[i] = ids.try_emplace(key, static_cast<std::uint32_t>(ids.size())).first->second;
    }
    return out;
}

std::vector<Vec3> points_of(const Scene& scene, const Polygon& p) {
    std::vector<Vec3> pts;
    for (auto v : p.vertices) pts.push_back(scene.vertices[v]);
    return pts;
}

void add_finding(std::vector<OrientationFinding>& out, OrientationFinding::Kind kind,
                 const Scene& scene, const std::vector<std::size_t>& polygons,
                 const std::vector<bool>& flip) {
    std::map<std::uint32_t, std::vector<std::size_t>> by_group;
    for (auto p : polygons) by_group[scene.polygons[p].group].push_back(p);
    for (auto& [group, list] : by_group) {
        std::sort(list.begin(), list.end());
        std::vector<std::size_t> to_flip;
        for (auto p : list)
            if (flip[p]) to_flip.push_back(p);
        out.push_back({kind, group, std::move(list), std::move(to_flip)});
    }
}

} // namespace

std::vector<OrientationFinding> check_orientation(const Scene& scene) {
    std::vector<OrientationFinding> findings;
    const std::size_t n = scene.polygons.size();

    // Each face's geometry, once: Newell normal (length twice the area), centroid, area; and
    // the box around every face, to tell a room (a surface around all the rest) from objects.
    struct FaceGeometry {
        Vec3 normal2, centroid;
        double area;
    };
    std::vector<FaceGeometry> face(n);
    Vec3 scene_lo{1e300, 1e300, 1e300}, scene_hi{-1e300, -1e300, -1e300};
    for (std::size_t f = 0; f < n; ++f) {
        const auto pts = points_of(scene, scene.polygons[f]);
        const Vec3 n2 = newell_normal(pts);
        face[f] = {n2, polygon_centroid(pts), 0.5 * length(n2)};
        for (const auto& p : pts)
            for (int c = 0; c < 3; ++c)
                scene_lo[c] = std::min(scene_lo[c], p[c]),
                scene_hi[c] = std::max(scene_hi[c], p[c]);
    }

    // 1. Faces wound against their own vn normals.
    std::vector<std::size_t> against_normals;
    for (std::size_t f = 0; f < n; ++f) {
        const auto& p = scene.polygons[f];
        if (length(p.vn_sum) == 0 || p.vertices.size() < 3) continue;
        if (dot(face[f].normal2, p.vn_sum) < 0) against_normals.push_back(f);
    }
    add_finding(findings, OrientationFinding::Kind::AgainstNormals, scene, against_normals,
                std::vector<bool>(n, false)); // vn may be the wrong part: report, never fix

    // 2. Connected surfaces over welded edges, and each face's winding relative to its
    // neighbours: two faces agree when they run along their shared edge in opposite
    // directions.
    const auto id = weld(scene);
    struct Use {
        std::size_t polygon;
        bool forward; // runs from the smaller welded id to the larger
    };
    std::unordered_map<std::uint64_t, std::vector<Use>> edges;
    for (std::size_t f = 0; f < n; ++f) {
        const auto& vs = scene.polygons[f].vertices;
        for (std::size_t k = 0; k < vs.size(); ++k) {
            const auto a = id[vs[k]], b = id[vs[(k + 1) % vs.size()]];
            if (a == b) continue;
            const auto key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            edges[key].push_back({f, a < b});
        }
    }
    UnionFind components(n);
    std::vector<std::vector<std::pair<std::size_t, bool>>> neighbours(n); // (face, same-direction)
    std::vector<bool> open_edge_of(n, false);
    for (const auto& [key, uses] : edges) {
        if (uses.size() != 2) {
            for (const auto& u : uses) open_edge_of[u.polygon] = true;
            continue;
        }
        if (uses[0].polygon == uses[1].polygon) continue;
        components.unite(uses[0].polygon, uses[1].polygon);
        const bool same = uses[0].forward == uses[1].forward;
        neighbours[uses[0].polygon].push_back({uses[1].polygon, same});
        neighbours[uses[1].polygon].push_back({uses[0].polygon, same});
    }
    std::map<std::size_t, std::vector<std::size_t>> members;
    for (std::size_t f = 0; f < n; ++f) members[components.find(f)].push_back(f);

    std::vector<std::size_t> against_neighbours, inside_out;
    std::vector<bool> flip(n, false);
    std::vector<int> parity(n, -1);
    for (const auto& [component, faces] : members) {
        if (faces.size() < 2) continue;
        // Breadth-first parity: 1 = flipped relative to the component's first face.
        bool orientable = true;
        std::deque<std::size_t> queue{faces.front()};
        parity[faces.front()] = 0;
        while (!queue.empty()) {
            const auto f = queue.front();
            queue.pop_front();
            for (const auto& [g, same] : neighbours[f]) {
                const int want = parity[f] ^ (same ? 1 : 0);
                if (parity[g] < 0) {
                    parity[g] = want;
                    queue.push_back(g);
                } else if (parity[g] != want) {
                    orientable = false;
                }
            }
        }
        if (!orientable) continue; // a Moebius-like tangle: no consistent answer to give
        // The minority (by area) disagrees with the rest.
        double area[2] = {0, 0};
        Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300}, centre{0, 0, 0};
        double total_area = 0;
        for (auto f : faces) {
            area[parity[f]] += face[f].area;
            centre = centre + face[f].centroid * face[f].area;
            total_area += face[f].area;
            for (auto v : scene.polygons[f].vertices)
                for (int c = 0; c < 3; ++c)
                    lo[c] = std::min(lo[c], scene.vertices[v][c]),
                    hi[c] = std::max(hi[c], scene.vertices[v][c]);
        }
        if (total_area > 0) centre = centre * (1 / total_area);
        const int minority = area[1] <= area[0] ? 1 : 0;

        // Facing inward is right for a room: a surface that encloses everything else (its
        // box holds the scene's box, give or take 1% of the scene's size: exporters let
        // water or furniture poke a few millimetres through a wall). Any other surface is
        // an object, which must face outward.
        const double tol = 0.01 * length(scene_hi - scene_lo);
        bool encloses_rest = true;
        for (int c = 0; c < 3; ++c)
            if (scene_lo[c] < lo[c] - tol || scene_hi[c] > hi[c] + tol) encloses_rest = false;
        // Which parity class faces the right way: for a room, the majority; for an object,
        // the one whose faces point away from the surface's centre. For a closed object the
        // score below is six times its signed volume, so that class gives a positive volume.
        int right = 1 - minority;
        if (!encloses_rest) {
            const bool closed =
                std::none_of(faces.begin(), faces.end(), [&](auto f) { return open_edge_of[f]; });
            double score = 0; // > 0: parity-0 faces as written face the right way
            for (auto f : faces)
                score +=
                    (parity[f] == 0 ? 1 : -1) * dot(face[f].normal2, face[f].centroid - centre);
            // A flat or nearly flat surface has no inside: keep its majority. A closed surface
            // must show a volume of at least 1% of its area times its size.
            const double scale = (closed ? 6 : 1) * total_area * length(hi - lo);
            if (std::abs(score) > 0.01 * scale) right = score > 0 ? 0 : 1;
        }
        for (auto f : faces) {
            if (parity[f] == right) continue;
            flip[f] = true;
            (parity[f] == minority ? against_neighbours : inside_out).push_back(f);
        }
    }
    add_finding(findings, OrientationFinding::Kind::AgainstNeighbours, scene, against_neighbours,
                flip);
    add_finding(findings, OrientationFinding::Kind::InsideOut, scene, inside_out, flip);
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
    }
    const auto& first = scene.polygons[finding.polygons.front()];
    return "group " + scene.groups[finding.group] + ": " + std::to_string(finding.polygons.size()) +
           " face(s) " + what + " (first at " + FileLoc{scene.path, first.line}.str() + ")";
}

std::size_t flip_groups(Scene& scene, const std::vector<std::string>& groups) {
    std::size_t flipped = 0;
    for (const auto& name : groups) {
        const auto it = std::find(scene.groups.begin(), scene.groups.end(), name);
        if (it == scene.groups.end()) {
            std::string known;
            for (const auto& g : scene.groups) known += (known.empty() ? "" : ", ") + g;
            throw InputError("--flip: no group '" + name + "' in " + scene.path +
                             " (it has: " + known + ")");
        }
        const auto group = static_cast<std::uint32_t>(it - scene.groups.begin());
        for (auto& p : scene.polygons)
            if (p.group == group) {
                std::reverse(p.vertices.begin(), p.vertices.end());
                ++flipped;
            }
    }
    return flipped;
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
