// Contact imprinting, step 1: where other faces touch or cross each face (its cut lines).
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/geometry/slab_points.hpp"
#include "mesh/imprint/box_pairs.hpp"
#include "mesh/imprint/imprint_parts.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace rad::imprinting {

bool convex(const std::vector<XY>& poly) {
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k)
        if (cross2(poly[k], poly[(k + 1) % n], poly[(k + 2) % n]) < 0) return false;
    return true;
}

namespace {

// Cyrus-Beck: the part of segment s inside the convex, counter-clockwise polygon.
bool clip_to_convex(Segment& s, const std::vector<XY>& poly) {
    double t0 = 0, t1 = 1;
    const double dx = s.b[0] - s.a[0], dy = s.b[1] - s.a[1];
    for (std::size_t k = 0; k < poly.size(); ++k) {
        const auto& p = poly[k];
        const auto& q = poly[(k + 1) % poly.size()];
        // Inside is to the left of p->q: n = (-(qy-py), qx-px) points inside.
        const double nx = -(q[1] - p[1]), ny = q[0] - p[0];
        const double num = nx * (s.a[0] - p[0]) + ny * (s.a[1] - p[1]);
        const double den = nx * dx + ny * dy;
        if (den == 0) {
            if (num < 0) return false;
            continue;
        }
        const double t = -num / den;
        if (den > 0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    const Segment in{{s.a[0] + t0 * dx, s.a[1] + t0 * dy}, {s.a[0] + t1 * dx, s.a[1] + t1 * dy}};
    s = in;
    return true;
}

// q's corners' heights over p's plane, those within [-below, above] of it set to 0 (on it).
struct Heights {
    std::vector<double> d;
    int above = 0, below = 0, on = 0;
};
Heights heights(const Face& p, const Face& q, double below, double above) {
    Heights h;
    for (const auto& x : q.points) {
        const double z = dot(x - p.frame.origin, p.frame.normal);
        h.d.push_back(z >= -below && z <= above ? 0.0 : z);
        h.above += h.d.back() > 0, h.below += h.d.back() < 0, h.on += h.d.back() == 0;
    }
    return h;
}

// Where convex q's corners at heights d meet the plane: its on-corners and edge crossings,
// the extremes of which are the segment.
bool crossing_segment(const Face& p, const Face& q, const std::vector<double>& d,
                      Segment& segment) {
    std::vector<Vec3> hits;
    for (std::size_t k = 0; k < q.points.size(); ++k) {
        const std::size_t l = (k + 1) % q.points.size();
        if (d[k] == 0) hits.push_back(q.points[k]);
        if ((d[k] < 0 && d[l] > 0) || (d[k] > 0 && d[l] < 0))
            hits.push_back(q.points[k] + (q.points[l] - q.points[k]) * (d[k] / (d[k] - d[l])));
    }
    if (hits.size() < 2) return false;
    const Vec3 along = hits[1] - hits[0];
    std::size_t lo = 0, hi = 0;
    for (std::size_t k = 1; k < hits.size(); ++k) {
        if (dot(hits[k] - hits[0], along) < dot(hits[lo] - hits[0], along)) lo = k;
        if (dot(hits[k] - hits[0], along) > dot(hits[hi] - hits[0], along)) hi = k;
    }
    segment = {p.frame.to2d(hits[lo]), p.frame.to2d(hits[hi])};
    return true;
}

// The gap q's edge may leave in front of p's plane and still touch it: `gap`, and at most
// 1/20 of how far q reaches out in front of the plane. A wall ending a hair below a ceiling
// touches it; a trim or a lamp as deep as its distance from the surface does not.
double gap_for(const std::vector<Vec3>& q, const Vec3& origin, const Vec3& normal, double gap) {
    double reach = 0;
    for (const auto& x : q) reach = std::max(reach, dot(x - origin, normal));
    return std::min(gap, reach / 20);
}

// Where face q meets face p's plane, as a segment in p's coordinates (false: it does not,
// or only at a point). Coplanar faces facing p give their outline instead (in `outline`).
// Within `tol` of the plane a corner is on it. Failing a contact so, an edge of q within
// gap_for in front of the plane lies on it: the gap is closed as a contact would be.
bool contact(const Face& p, const Face& q, double tol, double gap, Segment& segment,
             std::vector<Segment>& outline) {
    auto h = heights(p, q, tol, tol);
    if (!(h.above && h.below) && h.on < 2)
        if (const double g = gap_for(q.points, p.frame.origin, p.frame.normal, gap); g > tol)
            h = heights(p, q, tol, g);
    if (h.on == static_cast<int>(q.points.size())) {                  // coplanar
        if (dot(q.frame.normal, p.frame.normal) > -0.5) return false; // same side: no contact
        for (std::size_t k = 0; k < q.points.size(); ++k)
            outline.push_back(
                {p.frame.to2d(q.points[k]), p.frame.to2d(q.points[(k + 1) % q.points.size()])});
        return false;
    }
    if (!(h.above && h.below) && h.on < 2) return false;
    return crossing_segment(p, q, h.d, segment);
}

Face make_face(const Scene& scene, const Polygon& poly, const std::vector<std::uint32_t>& welded,
               double tol) {
    Face face{};
    for (auto v : poly.vertices) {
        face.points.push_back(scene.vertices[v]);
        face.welded.push_back(welded[v]);
    }
    std::sort(face.welded.begin(), face.welded.end());
    const Vec3 n2 = newell_normal(face.points);
    face.area = 0.5 * length(n2);
    if (face.points.size() < 3 || !(face.area > 0)) return face;
    face.frame.normal = normalized(n2);
    face.frame.origin = face.points[0];
    face.frame.u = orthogonal(face.frame.normal);
    face.frame.v = cross(face.frame.normal, face.frame.u);
    face.frame.offset = dot(face.frame.normal, face.frame.origin);
    face.planar = true;
    for (const auto& x : face.points)
        if (std::abs(dot(x - face.frame.origin, face.frame.normal)) > tol) face.planar = false;
    face.box = bounds(face.points);
    return face;
}

// A face's corners, into `points` (reused: this runs for every candidate pair).
void corners_of(const Scene& scene, std::uint32_t f, std::vector<Vec3>& points) {
    points.clear();
    for (const auto v : scene.polygons[f].vertices) points.push_back(scene.vertices[v]);
}

// Whether `contact` can find anything between face p and face q: q crosses p's plane, or
// lies on it along an edge (within gap_for in front of it), or lies in it facing the other way.
// Most pairs of nearby faces do not: those of a curved surface, and the tiles of one floor
// that meet at a corner. The plane as make_face has it (Newell's normal, through the first
// corner).
bool reaches_plane(const Scene& scene, std::uint32_t p, std::uint32_t q, double tol, double gap,
                   std::vector<Vec3>& points) {
    corners_of(scene, p, points);
    const Vec3 normal = normalized(newell_normal(points));
    const Vec3 origin = points[0];
    corners_of(scene, q, points);
    const double within = std::max(tol, gap_for(points, origin, normal, gap));
    int above = 0, below = 0, on = 0, near = 0;
    for (const auto& x : points) {
        const double h = dot(x - origin, normal);
        above += h > tol, below += h < -tol, on += std::abs(h) <= tol;
        near += h >= -tol && h <= within;
    }
    if ((above && below) || (on >= 2 && on < static_cast<int>(points.size()))) return true;
    if (near == static_cast<int>(points.size())) // coplanar: only a face facing p's front counts
        return dot(normalized(newell_normal(points)), normal) <= -0.5;
    return near >= 2;
}

// One object (or two faces meeting at an edge): a welded corner in common.
bool shares_welded_corner(const Scene& scene, const std::vector<std::uint32_t>& welded,
                          std::uint32_t a, std::uint32_t b) {
    for (const auto u : scene.polygons[a].vertices)
        for (const auto v : scene.polygons[b].vertices)
            if (welded[u] == welded[v]) return true;
    return false;
}

// Each face's welded corner that most faces have (the lowest of equals): faces with the same
// one share a corner, so the broad phase need not pair them (a fan's slivers all have its
// hub).
std::vector<std::uint32_t> busiest_corners(const Scene& scene,
                                           const std::vector<std::uint32_t>& welded) {
    std::vector<std::uint32_t> faces_at;
    for (const auto& poly : scene.polygons)
        for (const auto v : poly.vertices) {
            if (welded[v] >= faces_at.size()) faces_at.resize(welded[v] + 1, 0);
            ++faces_at[welded[v]];
        }
    std::vector<std::uint32_t> busiest(scene.polygons.size(), kNoGroup);
    for (std::size_t f = 0; f < scene.polygons.size(); ++f)
        for (const auto v : scene.polygons[f].vertices) {
            const auto w = welded[v], b = busiest[f];
            if (b == kNoGroup || faces_at[w] > faces_at[b] || (faces_at[w] == faces_at[b] && w < b))
                busiest[f] = w;
        }
    return busiest;
}

// The boxes of a face's pieces: slabs across its box's longest axis, as many as its box is
// larger than the face (up to 16). The box of a sliver lying diagonally is mostly empty: a
// cylinder's cap drawn as a fan put every sliver's box over the side's quads, and their pairs
// grew as the square of the segments.
void piece_boxes(const std::vector<Vec3>& points, double area, double reach,
                 std::vector<Box>& out) {
    out.clear();
    const Box whole = bounds(points);
    const Vec3 extent = whole.hi - whole.lo;
    int axis = 0;
    for (int c = 1; c < 3; ++c)
        if (extent[c] > extent[axis]) axis = c;
    const double box_area = extent[0] * extent[1] + extent[1] * extent[2] + extent[2] * extent[0];
    const int pieces =
        static_cast<int>(std::clamp(std::floor(std::sqrt(box_area / (4 * area))), 1.0, 16.0));
    if (pieces == 1) {
        out.push_back(whole); // most faces
    } else {
        for (int k = 0; k < pieces; ++k) {
            const double lo = whole.lo[axis] + extent[axis] * k / pieces;
            const double hi =
                k + 1 == pieces ? whole.hi[axis] : whole.lo[axis] + extent[axis] * (k + 1) / pieces;
            Box box;
            for_each_slab_point(points, axis, lo, hi, [&](const Vec3& p) { box.add(p); });
            out.push_back(box);
        }
    }
    for (auto& box : out)
        for (int c = 0; c < 3; ++c) box.lo[c] -= reach / 2, box.hi[c] += reach / 2;
}

// Candidate pairs: faces whose pieces' boxes overlap within `tol` (for_each_overlapping_pair),
// not of one object (no welded corner in common), each as (a face, one that reaches its
// plane). Faces of no area take no part. Sorted, so they do not depend on the order the pairs
// are found in.
std::vector<std::pair<std::uint32_t, std::uint32_t>>
touching_pairs(const Scene& scene, const std::vector<std::uint32_t>& welded, double tol,
               double gap) {
    std::vector<Box> boxes, pieces;
    std::vector<std::uint32_t> face_of;                    // each box's face
    std::vector<bool> split(scene.polygons.size(), false); // faces of several boxes
    std::vector<Vec3> points;
    const auto busiest = busiest_corners(scene, welded);
    std::vector<std::uint32_t> groups;
    for (std::uint32_t f = 0; f < scene.polygons.size(); ++f) {
        corners_of(scene, f, points);
        const double area = points.size() < 3 ? 0 : 0.5 * length(newell_normal(points));
        if (!(area > 0)) continue;
        piece_boxes(points, area, std::max(tol, gap), pieces);
        split[f] = pieces.size() > 1;
        for (const auto& box : pieces)
            boxes.push_back(box), face_of.push_back(f), groups.push_back(busiest[f]);
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    auto add_if_reaching = [&](std::uint32_t a, std::uint32_t b) {
        if (reaches_plane(scene, a, b, tol, gap, points)) pairs.emplace_back(a, b);
        if (reaches_plane(scene, b, a, tol, gap, points)) pairs.emplace_back(b, a);
    };
    // A pair of whole boxes is met once; one with a split face maybe more often: kept aside.
    std::vector<std::uint64_t> again;
    for_each_overlapping_pair(
        boxes,
        [&](std::uint32_t a, std::uint32_t b) {
            const auto fa = face_of[a], fb = face_of[b];
            if (fa == fb || shares_welded_corner(scene, welded, fa, fb)) return;
            if (!split[fa] && !split[fb])
                add_if_reaching(std::min(fa, fb), std::max(fa, fb));
            else
                again.push_back((std::uint64_t(std::min(fa, fb)) << 32) | std::max(fa, fb));
        },
        groups);
    std::sort(again.begin(), again.end());
    again.erase(std::unique(again.begin(), again.end()), again.end());
    for (const auto key : again)
        add_if_reaching(static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key));
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

// Faces sharing a welded edge, for walking a surface: each welded point's faces.
class FacesAtPoints {
  public:
    FacesAtPoints(const Scene& scene, const std::vector<std::uint32_t>& welded)
        : scene_(scene), welded_(welded) {
        std::uint32_t count = 0;
        for (const auto w : welded) count = std::max(count, w + 1);
        start_.assign(count + 1, 0);
        for (const auto& poly : scene.polygons)
            for (const auto v : poly.vertices) ++start_[welded[v] + 1];
        for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
        faces_.resize(start_.back());
        auto next = start_;
        for (std::uint32_t f = 0; f < scene.polygons.size(); ++f)
            for (const auto v : scene.polygons[f].vertices) faces_[next[welded[v]]++] = f;
    }
    // The faces that have the welded edge a-b (corners next to each other), ascending.
    void with_edge(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out) const {
        out.clear();
        for (auto k = start_[a]; k < start_[a + 1]; ++k) {
            const auto g = faces_[k];
            if (k > start_[a] && faces_[k - 1] == g) continue;
            const auto& vs = scene_.polygons[g].vertices;
            for (std::size_t i = 0; i < vs.size(); ++i) {
                const auto u = welded_[vs[i]], w = welded_[vs[(i + 1) % vs.size()]];
                if ((u == a && w == b) || (u == b && w == a)) {
                    out.push_back(g);
                    break;
                }
            }
        }
    }

  private:
    const Scene& scene_;
    const std::vector<std::uint32_t>& welded_;
    std::vector<std::uint32_t> start_, faces_;
};

// The cut lines of the faces that other objects touch. A cut parallel to a side of a convex
// face runs on to its outline, and on across the coplanar faces it continues into (the tiles
// of one floor): a rectangle cut by lines parallel to its sides stays rectangles, so regular
// grids. Other cuts stay as they are (slanted lines run on would make thin cells); the regions
// they bound are triangulated. Only the faces a contact or a run-on line reaches are looked at
// closely: on a large scene, nearly none.
class CutFinder {
  public:
    CutFinder(const Scene& scene, const std::vector<std::uint32_t>& welded, double tol, double gap,
              double size)
        : scene_(scene), welded_(welded), tol_(tol), gap_(gap), size_(size) {}
    void add_contacts(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& touching) {
        for (const auto& [f, q] : touching) {
            if (!face(f).face.planar) continue;
            Segment s;
            std::vector<Segment> found;
            if (contact(face(f).face, face(q).face, tol_, gap_, s, found)) found.push_back(s);
            for (const auto& c : found) add_cut(f, c, false);
        }
    }
    void run_on();
    CutLines result();

  private:
    struct Entry {
        Face face;
        std::vector<XY> outline; // in the face's plane (planar faces)
        bool convex = false;
        std::vector<Segment> cuts;
        std::vector<std::array<Vec3, 2>> chords; // the run-on lines, in 3D
    };
    Entry& face(std::uint32_t f);
    std::vector<std::uint32_t> surface_of(std::uint32_t f, const FacesAtPoints& adjacency,
                                          std::vector<char>& seen);
    bool parallel_to_a_side(const Entry& e, const Segment& c) const;
    bool along_outline(const Entry& e, const Segment& c) const;
    void add_cut(std::uint32_t f, Segment c, bool run_on);

    const Scene& scene_;
    const std::vector<std::uint32_t>& welded_;
    double tol_, gap_, size_;
    std::unordered_map<std::uint32_t, Entry> entries_; // made when first needed
    CutLines lines_;                                   // the contacts as found
};

CutFinder::Entry& CutFinder::face(std::uint32_t f) {
    const auto [it, fresh] = entries_.try_emplace(f);
    auto& e = it->second;
    if (!fresh) return e;
    e.face = make_face(scene_, scene_.polygons[f], welded_, tol_);
    if (e.face.planar) {
        for (const auto& x : e.face.points) e.outline.push_back(e.face.frame.to2d(x));
        e.convex = convex(e.outline);
    }
    return e;
}

bool CutFinder::parallel_to_a_side(const Entry& e, const Segment& c) const {
    const double dx = c.b[0] - c.a[0], dy = c.b[1] - c.a[1];
    const double len = std::hypot(dx, dy);
    for (std::size_t k = 0; k < e.outline.size(); ++k) {
        const auto& e0 = e.outline[k];
        const auto& e1 = e.outline[(k + 1) % e.outline.size()];
        const double ex = e1[0] - e0[0], ey = e1[1] - e0[1];
        if (std::abs(dx * ey - dy * ex) <= 1e-9 * len * std::hypot(ex, ey)) return true;
    }
    return false;
}

// Along the outline already: nothing to cut.
bool CutFinder::along_outline(const Entry& e, const Segment& c) const {
    for (std::size_t k = 0; k < e.outline.size(); ++k) {
        const auto& e0 = e.outline[k];
        const auto& e1 = e.outline[(k + 1) % e.outline.size()];
        const double edge = std::hypot(e1[0] - e0[0], e1[1] - e0[1]);
        if (std::abs(cross2(e0, e1, c.a)) <= tol_ * edge &&
            std::abs(cross2(e0, e1, c.b)) <= tol_ * edge)
            return true;
    }
    return false;
}

// `run_on`: a line run on from a coplanar neighbour (it need not reach in by itself).
void CutFinder::add_cut(std::uint32_t f, Segment c, bool run_on) {
    auto& e = face(f);
    const double dx = c.b[0] - c.a[0], dy = c.b[1] - c.a[1];
    const double len = std::hypot(dx, dy);
    if (len <= tol_) return;
    const bool parallel = parallel_to_a_side(e, c);
    if (run_on && !(e.convex && parallel)) return;
    // Only a contact that reaches into the face (by more than the tolerance) cuts it.
    if (!run_on) {
        if (e.convex && !clip_to_convex(c, e.outline)) return;
        if (std::hypot(c.b[0] - c.a[0], c.b[1] - c.a[1]) <= tol_) return;
        lines_.contacts.push_back(
            {e.face.frame.to3d(c.a[0], c.a[1]), e.face.frame.to3d(c.b[0], c.b[1])});
    }
    if (e.convex && parallel) {
        const double reach = 4 * size_ / len;
        c = {{c.a[0] - reach * dx, c.a[1] - reach * dy},
             {c.b[0] + reach * dx, c.b[1] + reach * dy}};
        if (!clip_to_convex(c, e.outline)) return;
    }
    if (std::hypot(c.b[0] - c.a[0], c.b[1] - c.a[1]) <= tol_) return;
    if (along_outline(e, c)) return;
    e.cuts.push_back(c);
    if (e.convex && parallel)
        e.chords.push_back({e.face.frame.to3d(c.a[0], c.a[1]), e.face.frame.to3d(c.b[0], c.b[1])});
}

// The planar faces reached from f across welded edges without leaving its plane, f's
// included, in index order. As a union of each edge's faces with the first planar face that
// has the edge (by index) when they are coplanar with it: the surfaces the imprinting was
// first written with.
std::vector<std::uint32_t> CutFinder::surface_of(std::uint32_t f, const FacesAtPoints& adjacency,
                                                 std::vector<char>& seen) {
    std::vector<std::uint32_t> surface{f}, stack{f}, sharing, planar;
    seen[f] = 1;
    auto coplanar = [&](std::uint32_t g, std::uint32_t h) {
        const auto &a = face(g).face, &b = face(h).face;
        return dot(a.frame.normal, b.frame.normal) > 1 - 1e-9 &&
               std::abs(a.frame.offset - b.frame.offset) <= tol_;
    };
    auto reach = [&](std::uint32_t h) {
        if (seen[h]) return;
        seen[h] = 1;
        surface.push_back(h);
        stack.push_back(h);
    };
    while (!stack.empty()) {
        const auto g = stack.back();
        stack.pop_back();
        const auto& vs = scene_.polygons[g].vertices;
        for (std::size_t k = 0; k < vs.size(); ++k) {
            adjacency.with_edge(welded_[vs[k]], welded_[vs[(k + 1) % vs.size()]], sharing);
            planar.clear();
            for (const auto h : sharing)
                if (face(h).face.planar) planar.push_back(h);
            if (planar.empty()) continue;
            const auto first = planar.front();
            if (g == first) {
                for (const auto h : planar)
                    if (h != g && coplanar(g, h)) reach(h);
            } else if (coplanar(g, first)) {
                reach(first);
            }
        }
    }
    std::sort(surface.begin(), surface.end());
    return surface;
}

// Coplanar faces sharing an edge (welded) form one surface; its run-on lines cross all.
void CutFinder::run_on() {
    std::vector<std::uint32_t> with_chords;
    for (const auto& [f, e] : entries_)
        if (!e.chords.empty()) with_chords.push_back(f);
    if (with_chords.empty()) return;
    std::sort(with_chords.begin(), with_chords.end());
    const FacesAtPoints adjacency(scene_, welded_);
    std::vector<char> seen(scene_.polygons.size(), 0);
    for (const auto start : with_chords) {
        if (seen[start]) continue;
        const auto list = surface_of(start, adjacency, seen);
        if (list.size() < 2) continue;
        // Each line runs on into the others, not back into its own face: cut there already,
        // run on again it would be re-clipped a rounding error away (a second, near-duplicate
        // point on the outline).
        std::vector<std::pair<std::array<Vec3, 2>, std::uint32_t>> lines;
        for (const auto f : list)
            for (const auto& chord : face(f).chords) lines.emplace_back(chord, f);
        for (const auto& [line, from] : lines)
            for (const auto f : list)
                if (f != from) {
                    const auto& frame = face(f).face.frame;
                    add_cut(f, {frame.to2d(line[0]), frame.to2d(line[1])}, true);
                }
    }
}

CutLines CutFinder::result() {
    CutLines lines = std::move(lines_);
    for (auto& [f, e] : entries_)
        if (!e.cuts.empty()) {
            lines.cuts.emplace(f, std::move(e.cuts));
            lines.faces.emplace(f, std::move(e.face));
        }
    entries_.clear();
    return lines;
}

} // namespace

CutLines find_cut_lines(const Scene& scene, const std::vector<std::uint32_t>& welded, double tol,
                        double gap, double size) {
    CutFinder finder(scene, welded, tol, gap, size);
    finder.add_contacts(touching_pairs(scene, welded, tol, gap));
    finder.run_on();
    return finder.result();
}

} // namespace rad::imprinting
