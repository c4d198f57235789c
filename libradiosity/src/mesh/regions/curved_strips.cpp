// Pass 0 of mesh_surfaces: a curved surface drawn as long thin facets (a tunnel's vault, a
// column's shaft) taken as wider planar faces across them, so that its patches are not slivers.
#include "mesh/geometry/point_buckets.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <unordered_map>

namespace rad::surfaces {

namespace {

// A long thin planar quad of the input (a quad face, or two triangles sharing its diagonal),
// by welded points, turned so that its long sides are ridge 0 = (q0, q1) and ridge 1 = (q3, q2):
// each ridge's first point is joined to the other's first by a short side.
struct Strip {
    std::array<std::uint32_t, 4> q{};
    std::array<std::uint32_t, 2> faces{kNone, kNone};
    std::uint32_t group = 0, material = 0;
    Vec3 normal{}; // unit
    double area = 0;
    std::array<std::uint32_t, 2> link{kNone, kNone}; // the strip across each ridge
    std::array<std::uint32_t, 2> ridge(int side) const {
        return side == 0 ? std::array{q[0], q[1]} : std::array{q[3], q[2]};
    }
};

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return length(p - (a + ab * t));
}

// Whether a face may be (half of) a strip: its height over its longest side at least three
// times under, and under a tenth of its group's cell.
bool thin_face(const radfmt::Patch& face, double longest,
               const std::vector<double>& cell_of_group) {
    const double cell = face.group < cell_of_group.size() ? cell_of_group[face.group] : 0;
    const double height = (face.corner_count() == 3 ? 2 : 1) * face.area / longest;
    return cell > 0 && height < cell / 10 && longest >= 3 * height;
}

class StripFinder {
  public:
    StripFinder(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                const std::vector<Vec3>& points, const std::vector<double>& cell_of_group)
        : faces_(faces), weld_(weld), points_(points), cell_of_group_(cell_of_group) {}

    std::vector<std::uint32_t> welded(std::uint32_t f) const {
        std::vector<std::uint32_t> out;
        for (const auto c : faces_.corners(f)) out.push_back(weld_[c]);
        return out;
    }

    // Thin quad faces, and thin triangles paired: candidate strips (make_strip checks them).
    std::vector<Strip> candidates() const {
        std::vector<Strip> out;
        std::vector<std::pair<EdgeKey, std::uint32_t>> long_edges; // of thin triangles
        for (std::uint32_t f = 0; f < faces_.patches.size(); ++f) {
            const auto& face = faces_.patches[f];
            if (face.is_polygon() || !thin_face(face, longest_edge(faces_, face), cell_of_group_))
                continue;
            const auto w = welded(f);
            if (w.size() == 4) {
                Strip s;
                std::copy(w.begin(), w.end(), s.q.begin());
                s.faces[0] = f;
                out.push_back(s);
                continue;
            }
            for (int e = 0; e < 3; ++e)
                if (e != shortest_side(w))
                    long_edges.emplace_back(edge_key(w[e], w[(e + 1) % 3]), f);
        }
        for (const auto& [f, g] : triangle_pairs(long_edges))
            if (auto s = pair_of(f, g)) out.push_back(*s);
        return out;
    }

  private:
    int shortest_side(const std::vector<std::uint32_t>& w) const {
        int best = 0;
        double shortest = 1e300;
        for (int k = 0; k < int(w.size()); ++k) {
            const double l = length(points_[w[(k + 1) % w.size()]] - points_[w[k]]);
            if (l < shortest) shortest = l, best = k;
        }
        return best;
    }

    // A strip's two triangles share its diagonal, which is hardly longer than its long sides
    // (rounding may make it shorter): each thin triangle is paired across one of its two long
    // edges with the triangle there that lies most nearly in its plane (a strip's other half:
    // in it; the next strip's: turned by the bend), where each is the other's choice.
    std::vector<std::pair<std::uint32_t, std::uint32_t>>
    triangle_pairs(std::vector<std::pair<EdgeKey, std::uint32_t>> long_edges) const {
        std::sort(long_edges.begin(), long_edges.end());
        std::unordered_map<std::uint32_t, std::pair<double, std::uint32_t>> best; // by cosine
        for (std::size_t i = 0; i + 1 < long_edges.size(); ++i) {
            const auto key = long_edges[i].first;
            if (long_edges[i + 1].first != key || (i > 0 && long_edges[i - 1].first == key) ||
                (i + 2 < long_edges.size() && long_edges[i + 2].first == key))
                continue;
            const auto f = long_edges[i].second, g = long_edges[i + 1].second;
            const double c =
                dot(normalized(faces_.patches[f].normal), normalized(faces_.patches[g].normal));
            for (const auto& [a, b] : {std::pair{f, g}, std::pair{g, f}}) {
                const auto it = best.find(a);
                if (it == best.end() || c > it->second.first) best[a] = {c, b};
            }
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        for (const auto& [f, choice] : best)
            if (f < choice.second && best.at(choice.second).second == f)
                pairs.emplace_back(f, choice.second);
        std::sort(pairs.begin(), pairs.end()); // the map's order is not the input's
        return pairs;
    }

    // Triangles a, b, c and b, a, d (one winding) sharing a, b as the quad a, d, b, c.
    std::optional<Strip> pair_of(std::uint32_t f, std::uint32_t g) const {
        const auto t = welded(f), u = welded(g);
        for (int k = 0; k < 3; ++k) {
            const auto a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
            for (int m = 0; m < 3; ++m)
                if (u[m] == b && u[(m + 1) % 3] == a) {
                    Strip s;
                    s.q = {a, u[(m + 2) % 3], b, c};
                    s.faces = {f, g};
                    return s;
                }
        }
        return std::nullopt;
    }

    const radfmt::MeshData& faces_;
    const std::vector<std::uint32_t>& weld_;
    const std::vector<Vec3>& points_;
    const std::vector<double>& cell_of_group_;
};

// Completes a candidate: its ridges along its long sides, its normal and area; false unless it
// is planar, convex, one material, at least three times as long as wide and thinner than a
// tenth of its cell (its patches would be slivers).
bool make_strip(Strip& s, const radfmt::MeshData& faces, const std::vector<Vec3>& points,
                const std::vector<double>& cell_of_group) {
    const auto& first = faces.patches[s.faces[0]];
    s.group = first.group, s.material = first.material;
    if (s.faces[1] != kNone) {
        const auto& second = faces.patches[s.faces[1]];
        if (second.group != s.group || second.material != s.material) return false;
        if (dot(normalized(first.normal), normalized(second.normal)) <
            std::cos(0.5 * std::numbers::pi / 180))
            return false;
    }
    std::array<Vec3, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = points[s.q[k]];
    const Vec3 n = newell_normal(p);
    s.area = 0.5 * length(n);
    if (!(s.area > 0)) return false;
    s.normal = n * (0.5 / s.area);
    for (int k = 0; k < 4; ++k) // strictly convex: every corner turns the same way
        if (!(dot(cross(p[(k + 1) % 4] - p[k], p[(k + 2) % 4] - p[(k + 1) % 4]), s.normal) > 0))
            return false;
    std::array<double, 4> side;
    for (int k = 0; k < 4; ++k) side[k] = length(p[(k + 1) % 4] - p[k]);
    if (side[1] + side[3] > side[0] + side[2]) {
        std::rotate(s.q.begin(), s.q.begin() + 1, s.q.end());
        std::rotate(side.begin(), side.begin() + 1, side.end());
    }
    const double long_side = 0.5 * (side[0] + side[2]), width = s.area / long_side;
    const double cell = s.group < cell_of_group.size() ? cell_of_group[s.group] : 0;
    return long_side >= 3 * width && cell > 0 && width < cell / 10;
}

// Strips joined across a ridge along which no other face runs, one material, wound alike,
// unless `kept(key)` (a crease, a ridge another surface's corner lies on).
template <class Kept>
void link_strips(std::vector<Strip>& strips, const FacesByEdge& by_edge, const Kept& kept) {
    std::vector<std::pair<EdgeKey, std::uint32_t>> ridges;
    for (std::uint32_t s = 0; s < strips.size(); ++s)
        for (int side = 0; side < 2; ++side) {
            const auto r = strips[s].ridge(side);
            ridges.emplace_back(edge_key(r[0], r[1]), s * 2 + side);
        }
    std::sort(ridges.begin(), ridges.end());
    for (std::size_t i = 0; i + 1 < ridges.size(); ++i) {
        const auto key = ridges[i].first;
        if (ridges[i + 1].first != key || (i > 0 && ridges[i - 1].first == key) ||
            (i + 2 < ridges.size() && ridges[i + 2].first == key) || kept(key))
            continue;
        const auto a = ridges[i].second, b = ridges[i + 1].second;
        std::size_t along = 0; // faces along the ridge (a sub-edge of theirs is it)
        by_edge.for_each_face(key, [&](std::uint32_t) { ++along; });
        if (along != 2) continue; // each strip has one face along each of its ridges
        auto &s = strips[a / 2], &t = strips[b / 2];
        if (s.group != t.group || s.material != t.material || !(dot(s.normal, t.normal) > 0))
            continue;
        s.link[a % 2] = b / 2;
        t.link[b % 2] = a / 2;
    }
}

// A chord lies on the concave side of the strips it spans (the side their neighbours bend
// to). Another face along a strip's end (a short side) that lies on that side covers the chord's
// end there (a tunnel's end wall, a column's cap); one on the convex side or in the strip's
// plane would be left with a gap along its edge (a floor round a column's foot, the next ring
// of a vault): strips with such an end are not joined.
class StripEnds {
  public:
    StripEnds(const radfmt::MeshData& faces, const std::vector<Vec3>& points,
              const FacesByEdge& by_edge, const PointBuckets& buckets, double on_line)
        : faces_(faces), points_(points), by_edge_(by_edge), buckets_(buckets), on_line_(on_line) {}

    // `side`: +1 when the strips bend to their front, -1 to their back.
    bool covered(const Strip& s, double side) const {
        const Vec3 concave = s.normal * side;
        for (const auto& [a, b] : {std::array{s.q[1], s.q[2]}, std::array{s.q[3], s.q[0]}}) {
            if (!buckets_.on_segment(a, b, on_line_).empty()) return false;
            const Vec3 middle = (points_[a] + points_[b]) * 0.5;
            const Vec3 along = normalized(points_[b] - points_[a]);
            bool open = false;
            by_edge_.for_each_face(edge_key(a, b), [&](std::uint32_t h) {
                if (h == s.faces[0] || h == s.faces[1]) return;
                // Into the face, square to the edge: within 60 degrees of the concave side.
                Vec3 into = faces_.patches[h].centroid - middle;
                into = into - along * dot(into, along);
                open = open || !(dot(into, concave) > 0.5 * length(into));
            });
            if (open) return false;
        }
        return true;
    }

  private:
    const radfmt::MeshData& faces_;
    const std::vector<Vec3>& points_;
    const FacesByEdge& by_edge_;
    const PointBuckets& buckets_;
    double on_line_;
};

Vec3 centre_of(const Strip& s, const std::vector<Vec3>& points) {
    return (points[s.q[0]] + points[s.q[1]] + points[s.q[2]] + points[s.q[3]]) * 0.25;
}

// Links dropped where a strip's end is not covered on the side the pair bends to.
void unlink_open_ends(std::vector<Strip>& strips, const std::vector<Vec3>& points,
                      const StripEnds& ends) {
    for (std::uint32_t s = 0; s < strips.size(); ++s)
        for (int side = 0; side < 2; ++side) {
            const auto t = strips[s].link[side];
            if (t == kNone || t < s) continue;
            const Vec3 bend = centre_of(strips[t], points) - centre_of(strips[s], points);
            const double bends = dot(strips[s].normal, bend) >= 0 ? 1.0 : -1.0;
            if (ends.covered(strips[s], bends) && ends.covered(strips[t], bends)) continue;
            strips[s].link[side] = kNone;
            for (auto& back : strips[t].link)
                if (back == s) back = kNone;
        }
}

// A chain of strips in order, and its ridges R0 .. RN (strip k lies between Rk and Rk+1),
// each as (its point on one end of the strips, its point on the other).
struct Chain {
    std::vector<std::uint32_t> strips;
    std::vector<std::array<std::uint32_t, 2>> ridges;
};

Chain walk_chain(std::vector<Strip>& strips, std::uint32_t start, int free_side,
                 std::vector<bool>& taken) {
    Chain chain;
    auto current = start;
    auto entry = strips[start].ridge(free_side);
    int side = free_side;
    chain.ridges.push_back(entry);
    for (;;) {
        taken[current] = true;
        chain.strips.push_back(current);
        auto exit = strips[current].ridge(1 - side);
        if (strips[current].ridge(side)[0] != entry[0]) std::swap(exit[0], exit[1]);
        chain.ridges.push_back(exit);
        const auto next = strips[current].link[1 - side];
        if (next == kNone || taken[next]) break; // an end, or round a closed ring
        const auto key = edge_key(exit[0], exit[1]);
        side = edge_key(strips[next].ridge(0)[0], strips[next].ridge(0)[1]) == key ? 0 : 1;
        entry = exit;
        current = next;
    }
    return chain;
}

std::vector<Chain> find_chains(std::vector<Strip>& strips) {
    std::vector<Chain> chains;
    std::vector<bool> taken(strips.size(), false);
    for (std::uint32_t s = 0; s < strips.size(); ++s) // open chains from an end
        for (int side = 0; side < 2 && !taken[s]; ++side)
            if (strips[s].link[side] == kNone) chains.push_back(walk_chain(strips, s, side, taken));
    for (std::uint32_t s = 0; s < strips.size(); ++s) // closed rings, from their first strip
        if (!taken[s]) chains.push_back(walk_chain(strips, s, 0, taken));
    return chains;
}

// A chord of a circular arc lies farther than this fraction of its width from the arc's middle
// when the arc turns more than 30 degrees, rad-shade's crease angle: (1 - cos 15) / (2 sin 15)
// = tan(7.5) / 2. Past it the faces made would shade as facets and lose over 1.1% of the area.
constexpr double kMaxOffsetOfWidth = 0.06583;
// And no strip turns more than half that from the chord (a fold of a cornice's profile, a short
// face beside a wide one, stays within the offset but is no arc).
const double kMinCosToChord = std::cos(15 * std::numbers::pi / 180);

// The planar quad across ridges i .. j of a chain, if it stays within `max_sag` of the cell (and
// kMaxOffsetOfWidth of its width) of every ridge between, each strip within 15 degrees of it,
// within `tolerance` of one plane, and no wider than the cell.
struct Chord {
    std::array<std::uint32_t, 4> corners{};
    double offset = 0; // the farthest a ridge between lies from it
};
std::optional<Chord> chord(const Chain& chain, std::size_t i, std::size_t j,
                           const std::vector<Vec3>& points, double cell, double max_sag,
                           double tolerance) {
    const auto &ri = chain.ridges[i], &rj = chain.ridges[j];
    const std::array<Vec3, 4> p{points[ri[0]], points[ri[1]], points[rj[1]], points[rj[0]]};
    const Vec3 n = newell_normal(p);
    const double area = 0.5 * length(n);
    const double width = area / (0.5 * (length(p[1] - p[0]) + length(p[2] - p[3])));
    if (!(area > 0) || width > cell) return std::nullopt;
    const Vec3 unit = n * (0.5 / area);
    for (int k = 0; k < 4; ++k) {
        if (std::abs(dot(p[k] - p[0], unit)) > tolerance) return std::nullopt;
        if (!(dot(cross(p[(k + 1) % 4] - p[k], p[(k + 2) % 4] - p[(k + 1) % 4]), unit) > 0))
            return std::nullopt;
    }
    for (auto k = i; k < j; ++k) { // each strip within 15 degrees of the chord's plane
        const auto &r0 = chain.ridges[k], &r1 = chain.ridges[k + 1];
        const std::array<Vec3, 4> strip{points[r0[0]], points[r0[1]], points[r1[1]], points[r1[0]]};
        if (!(std::abs(dot(normalized(newell_normal(strip)), unit)) >= kMinCosToChord))
            return std::nullopt;
    }
    Chord out;
    for (auto k = i + 1; k < j; ++k) {
        const auto& r = chain.ridges[k];
        out.offset = std::max({out.offset, distance_to_segment(points[r[0]], p[0], p[3]),
                               distance_to_segment(points[r[1]], p[1], p[2])});
    }
    if (out.offset > max_sag * cell || out.offset > kMaxOffsetOfWidth * width) return std::nullopt;
    out.corners = {ri[0], ri[1], rj[1], rj[0]};
    return out;
}

// The chain cut into runs of strips, each one chord: as few as the greedy cut from its start
// makes, as even in count as they pass. Boundaries are ridge indices 0 = b0 < b1 < .. = N.
std::vector<std::size_t> runs_of(const Chain& chain, const std::vector<Vec3>& points, double cell,
                                 double max_sag, double tolerance) {
    const std::size_t n = chain.strips.size();
    const auto fits = [&](std::size_t i, std::size_t j) {
        return j == i + 1 || chord(chain, i, j, points, cell, max_sag, tolerance).has_value();
    };
    std::vector<std::size_t> greedy{0};
    while (greedy.back() < n) {
        auto j = greedy.back() + 1;
        while (j < n && fits(greedy.back(), j + 1)) ++j;
        greedy.push_back(j);
    }
    const std::size_t runs = greedy.size() - 1;
    std::vector<std::size_t> even{0};
    for (std::size_t r = 1; r <= runs; ++r) even.push_back(n * r / runs);
    for (std::size_t r = 0; r < runs; ++r)
        if (!fits(even[r], even[r + 1])) return greedy;
    return even;
}

// The chord as a face of the strips' group and material, wound as they are (`facing`: the sum
// of their normals).
radfmt::Patch quad_patch(const std::array<std::uint32_t, 4>& corners, const Strip& like,
                         const Vec3& facing, const std::vector<std::uint32_t>& vertex_of,
                         const std::vector<Vec3>& points) {
    radfmt::Patch patch;
    std::array<Vec3, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = points[corners[k]];
    Vec3 n = newell_normal(p);
    std::array<std::uint32_t, 4> c = corners;
    if (dot(n, facing) < 0) {
        std::reverse(c.begin(), c.end());
        std::reverse(p.begin(), p.end());
        n = n * -1;
    }
    for (int k = 0; k < 4; ++k) patch.corners[k] = vertex_of[c[k]];
    patch.group = like.group;
    patch.material = like.material;
    patch.area = 0.5 * length(n);
    patch.normal = n * (0.5 / patch.area);
    patch.centroid = polygon_centroid(p);
    return patch;
}

// Whether strips i .. j - 1 of the chain lie in one plane as pass 1 joins faces (normals within
// its angle tolerance of the first's): one region as drawn, left to it.
bool planar_run(const Chain& chain, std::size_t i, std::size_t j, const std::vector<Strip>& strips,
                double min_cos) {
    const auto& first = strips[chain.strips[i]].normal;
    for (auto k = i + 1; k < j; ++k)
        if (dot(strips[chain.strips[k]].normal, first) < min_cos) return false;
    return true;
}

// The faces of merged runs: each run's chord in place of its first face, the rest dropped.
struct RunReplacer {
    RunReplacer(std::size_t faces, const std::vector<Strip>& strips,
                const std::vector<std::uint32_t>& vertex_of, const std::vector<Vec3>& points,
                StripMerge& merged)
        : replaced(faces), dropped(faces, false), strips_(strips), vertex_of_(vertex_of),
          points_(points), merged_(merged) {}
    void replace(const Chain& chain, std::size_t i, std::size_t j, const Chord& chord) {
        std::uint32_t first = kNone;
        Vec3 facing{0, 0, 0};
        for (auto k = i; k < j; ++k) {
            const auto& s = strips_[chain.strips[k]];
            merged_.area_before += s.area;
            facing = facing + s.normal;
            for (const auto f : s.faces)
                if (f != kNone) dropped[f] = true, first = std::min(first, f), ++merged_.facets;
        }
        const auto& like = strips_[chain.strips[i]];
        replaced[first] = quad_patch(chord.corners, like, facing, vertex_of_, points_);
        merged_.area_after += replaced[first]->area;
        merged_.worst_offset = std::max(merged_.worst_offset, chord.offset);
        ++merged_.faces;
    }
    std::vector<std::optional<radfmt::Patch>> replaced;
    std::vector<bool> dropped;

  private:
    const std::vector<Strip>& strips_;
    const std::vector<std::uint32_t>& vertex_of_;
    const std::vector<Vec3>& points_;
    StripMerge& merged_;
};

} // namespace

std::optional<radfmt::MeshData>
merge_curved_strips(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                    const Points& welded, const std::vector<double>& cell_of_group,
                    const SurfaceOptions& options, double scene_size, StripMerge& merged) {
    const double max_sag = options.max_sag, tolerance = options.plane_tolerance * scene_size;
    if (!(max_sag > 0)) return std::nullopt;
    const auto& points = welded.position;
    const auto count = static_cast<std::uint32_t>(points.size());
    std::vector<std::uint32_t> vertex_of(count, kNone); // a vertex of each welded point
    for (std::uint32_t v = 0; v < faces.vertices.size(); ++v)
        if (vertex_of[weld[v]] == kNone) vertex_of[weld[v]] = v;
    const StripFinder finder(faces, weld, points, cell_of_group);
    std::vector<Strip> strips;
    for (auto s : finder.candidates())
        if (make_strip(s, faces, points, cell_of_group)) strips.push_back(s);
    if (strips.empty()) return std::nullopt;
    // A surface stops where a region would: along a contact line, or where another surface's
    // corner lies on its ridge (something meets it there).
    std::vector<std::uint32_t> ids(count);
    for (std::uint32_t k = 0; k < count; ++k) ids[k] = k;
    const PointBuckets buckets(ids, welded);
    const double on_line = 1e-7 * scene_size;
    const auto creases = crease_edges(options.creases, buckets, on_line);
    const FacesByEdge by_edge(split_face_edges(faces, weld, buckets, on_line));
    link_strips(strips, by_edge, [&](EdgeKey key) {
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
        return std::binary_search(creases.begin(), creases.end(), key) ||
               !buckets.on_segment(a, b, on_line).empty();
    });
    unlink_open_ends(strips, points, StripEnds(faces, points, by_edge, buckets, on_line));

    // Faces of merged runs: the run's chord in place of its first face, the rest dropped.
    RunReplacer replacer(faces.patches.size(), strips, vertex_of, points, merged);
    const double min_cos = std::cos(options.angle_tolerance * std::numbers::pi / 180);
    for (const auto& chain : find_chains(strips)) {
        const double cell = cell_of_group[strips[chain.strips.front()].group];
        const auto bounds = runs_of(chain, points, cell, max_sag, tolerance);
        bool any = false;
        for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
            const auto i = bounds[r], j = bounds[r + 1];
            if (j == i + 1 || planar_run(chain, i, j, strips, min_cos)) continue;
            replacer.replace(chain, i, j, *chord(chain, i, j, points, cell, max_sag, tolerance));
            any = true;
        }
        merged.chains += any;
    }
    const auto& replaced = replacer.replaced;
    const auto& dropped = replacer.dropped;
    if (!merged.faces) return std::nullopt;
    radfmt::MeshData out;
    out.vertices = faces.vertices;
    out.groups = faces.groups;
    out.materials = faces.materials;
    out.polygon_corners = faces.polygon_corners;
    for (std::size_t f = 0; f < faces.patches.size(); ++f) {
        if (replaced[f])
            out.patches.push_back(*replaced[f]);
        else if (!dropped[f])
            out.patches.push_back(faces.patches[f]);
    }
    return out;
}

} // namespace rad::surfaces
