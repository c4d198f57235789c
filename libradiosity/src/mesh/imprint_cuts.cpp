// Contact imprinting, step 1: where other faces touch or cross each face (its cut lines).
#include "../union_find.hpp"
#include "imprint_parts.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rad::imprinting {

double cross2(const XY& o, const XY& a, const XY& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

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

// Where face q meets face p's plane, as a segment in p's coordinates (false: it does not,
// or only at a point). Coplanar faces facing p give their outline instead (in `outline`).
bool contact(const Face& p, const Face& q, double tol, Segment& segment,
             std::vector<Segment>& outline) {
    std::vector<double> d;
    int above = 0, below = 0, on = 0;
    for (const auto& x : q.points) {
        const double h = dot(x - p.frame.origin, p.frame.normal);
        d.push_back(std::abs(h) <= tol ? 0.0 : h);
        above += d.back() > 0, below += d.back() < 0, on += d.back() == 0;
    }
    if (on == static_cast<int>(q.points.size())) {                    // coplanar
        if (dot(q.frame.normal, p.frame.normal) > -0.5) return false; // same side: no contact
        for (std::size_t k = 0; k < q.points.size(); ++k)
            outline.push_back(
                {p.frame.to2d(q.points[k]), p.frame.to2d(q.points[(k + 1) % q.points.size()])});
        return false;
    }
    if (!(above && below) && on < 2) return false;
    std::vector<Vec3> hits;
    for (std::size_t k = 0; k < q.points.size(); ++k) {
        const std::size_t l = (k + 1) % q.points.size();
        if (d[k] == 0) hits.push_back(q.points[k]);
        if ((d[k] < 0 && d[l] > 0) || (d[k] > 0 && d[l] < 0))
            hits.push_back(q.points[k] + (q.points[l] - q.points[k]) * (d[k] / (d[k] - d[l])));
    }
    if (hits.size() < 2) return false;
    // Convex q: the points lie on one line; its extremes are the segment.
    const Vec3 along = hits[1] - hits[0];
    std::size_t lo = 0, hi = 0;
    for (std::size_t k = 1; k < hits.size(); ++k) {
        if (dot(hits[k] - hits[0], along) < dot(hits[lo] - hits[0], along)) lo = k;
        if (dot(hits[k] - hits[0], along) > dot(hits[hi] - hits[0], along)) hi = k;
    }
    segment = {p.frame.to2d(hits[lo]), p.frame.to2d(hits[hi])};
    return true;
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

// Candidate pairs: overlapping boxes (a sweep along x), not of one object.
std::vector<std::vector<std::uint32_t>> touching_pairs(const std::vector<Face>& faces, double tol) {
    const std::size_t n = faces.size();
    std::vector<std::size_t> order(n);
    for (std::size_t f = 0; f < n; ++f) order[f] = f;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return faces[a].box.lo[0] < faces[b].box.lo[0];
    });
    std::vector<std::vector<std::uint32_t>> touching(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& a = faces[order[i]];
        if (!a.planar && a.points.size() < 3) continue;
        for (std::size_t j = i + 1; j < n && faces[order[j]].box.lo[0] <= a.box.hi[0] + tol; ++j) {
            const auto& b = faces[order[j]];
            bool overlap = true;
            for (int k = 1; k < 3; ++k)
                overlap =
                    overlap && b.box.lo[k] <= a.box.hi[k] + tol && a.box.lo[k] <= b.box.hi[k] + tol;
            if (!overlap) continue;
            std::vector<std::uint32_t> shared;
            std::set_intersection(a.welded.begin(), a.welded.end(), b.welded.begin(),
                                  b.welded.end(), std::back_inserter(shared));
            if (!shared.empty()) continue; // one object (or two faces meeting at an edge)
            touching[order[i]].push_back(static_cast<std::uint32_t>(order[j]));
            touching[order[j]].push_back(static_cast<std::uint32_t>(order[i]));
        }
    }
    return touching;
}

// The cut lines of every face. A cut parallel to a side of a convex face runs on to its
// outline, and on across the coplanar faces it continues into (the tiles of one floor): a
// rectangle cut by lines parallel to its sides stays rectangles, so regular grids. Other cuts
// stay as they are (slanted lines run on would make thin cells); the regions they bound are
// triangulated.
class CutFinder {
  public:
    CutFinder(CutLines& lines, double tol, double size) : lines_(lines), tol_(tol), size_(size) {
        const std::size_t n = lines.faces.size();
        lines.cuts.assign(n, {});
        chords_.resize(n);
        outlines_.resize(n);
        is_convex_.assign(n, 0);
        for (std::size_t f = 0; f < n; ++f) {
            if (!lines.faces[f].planar) continue;
            for (const auto& x : lines.faces[f].points)
                outlines_[f].push_back(lines.faces[f].frame.to2d(x));
            is_convex_[f] = convex(outlines_[f]);
        }
    }
    void add_contacts(const std::vector<std::vector<std::uint32_t>>& touching) {
        const auto& faces = lines_.faces;
        for (std::size_t f = 0; f < faces.size(); ++f) {
            if (!faces[f].planar) continue;
            for (const auto q : touching[f]) {
                if (faces[q].area == 0) continue;
                Segment s;
                std::vector<Segment> found;
                if (contact(faces[f], faces[q], tol_, s, found)) found.push_back(s);
                for (const auto& c : found) add_cut(f, c, false);
            }
        }
    }
    void run_on(const Scene& scene, const std::vector<std::uint32_t>& welded);

  private:
    bool parallel_to_a_side(std::size_t f, const Segment& c) const;
    bool along_outline(std::size_t f, const Segment& c) const;
    void add_cut(std::size_t f, Segment c, bool run_on);

    CutLines& lines_;
    double tol_, size_;
    std::vector<std::vector<std::array<Vec3, 2>>> chords_; // the run-on lines, in 3D
    std::vector<std::vector<XY>> outlines_;
    std::vector<char> is_convex_;
};

bool CutFinder::parallel_to_a_side(std::size_t f, const Segment& c) const {
    const auto& outline2d = outlines_[f];
    const double dx = c.b[0] - c.a[0], dy = c.b[1] - c.a[1];
    const double len = std::hypot(dx, dy);
    for (std::size_t k = 0; k < outline2d.size(); ++k) {
        const auto& e0 = outline2d[k];
        const auto& e1 = outline2d[(k + 1) % outline2d.size()];
        const double ex = e1[0] - e0[0], ey = e1[1] - e0[1];
        if (std::abs(dx * ey - dy * ex) <= 1e-9 * len * std::hypot(ex, ey)) return true;
    }
    return false;
}

// Along the outline already: nothing to cut.
bool CutFinder::along_outline(std::size_t f, const Segment& c) const {
    const auto& outline2d = outlines_[f];
    for (std::size_t k = 0; k < outline2d.size(); ++k) {
        const auto& e0 = outline2d[k];
        const auto& e1 = outline2d[(k + 1) % outline2d.size()];
        const double edge = std::hypot(e1[0] - e0[0], e1[1] - e0[1]);
        if (std::abs(cross2(e0, e1, c.a)) <= tol_ * edge &&
            std::abs(cross2(e0, e1, c.b)) <= tol_ * edge)
            return true;
    }
    return false;
}

// `run_on`: a line run on from a coplanar neighbour (it need not reach in by itself).
void CutFinder::add_cut(std::size_t f, Segment c, bool run_on) {
    const auto& outline2d = outlines_[f];
    const double dx = c.b[0] - c.a[0], dy = c.b[1] - c.a[1];
    const double len = std::hypot(dx, dy);
    if (len <= tol_) return;
    const bool parallel = parallel_to_a_side(f, c);
    if (run_on && !(is_convex_[f] && parallel)) return;
    // Only a contact that reaches into the face (by more than the tolerance) cuts it.
    if (!run_on) {
        if (is_convex_[f] && !clip_to_convex(c, outline2d)) return;
        if (std::hypot(c.b[0] - c.a[0], c.b[1] - c.a[1]) <= tol_) return;
    }
    if (is_convex_[f] && parallel) {
        const double reach = 4 * size_ / len;
        c = {{c.a[0] - reach * dx, c.a[1] - reach * dy},
             {c.b[0] + reach * dx, c.b[1] + reach * dy}};
        if (!clip_to_convex(c, outline2d)) return;
    }
    if (std::hypot(c.b[0] - c.a[0], c.b[1] - c.a[1]) <= tol_) return;
    if (along_outline(f, c)) return;
    lines_.cuts[f].push_back(c);
    const auto& frame = lines_.faces[f].frame;
    if (is_convex_[f] && parallel)
        chords_[f].push_back({frame.to3d(c.a[0], c.a[1]), frame.to3d(c.b[0], c.b[1])});
}

// Coplanar faces sharing an edge (welded) form one surface; its run-on lines cross all.
void CutFinder::run_on(const Scene& scene, const std::vector<std::uint32_t>& welded) {
    const auto& faces = lines_.faces;
    const std::size_t n = faces.size();
    UnionFind surfaces(n);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> first_with_edge;
    for (std::size_t f = 0; f < n; ++f) {
        if (!faces[f].planar) continue;
        const auto& vs = scene.polygons[f].vertices;
        for (std::size_t k = 0; k < vs.size(); ++k) {
            auto a = welded[vs[k]], b = welded[vs[(k + 1) % vs.size()]];
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto [it, fresh] = first_with_edge.emplace(key, f);
            if (fresh) continue;
            const auto& g = faces[it->second];
            if (dot(g.frame.normal, faces[f].frame.normal) > 1 - 1e-9 &&
                std::abs(g.frame.offset - faces[f].frame.offset) <= tol_)
                surfaces.unite(f, it->second);
        }
    }
    std::map<std::size_t, std::vector<std::size_t>> members;
    for (std::size_t f = 0; f < n; ++f)
        if (faces[f].planar) members[surfaces.find(f)].push_back(f);
    for (const auto& [root, list] : members) {
        if (list.size() < 2) continue;
        // Each line runs on into the others, not back into its own face: cut there already,
        // run on again it would be re-clipped a rounding error away (a second, near-duplicate
        // point on the outline).
        std::vector<std::pair<std::array<Vec3, 2>, std::size_t>> lines;
        for (const auto f : list)
            for (const auto& chord : chords_[f]) lines.emplace_back(chord, f);
        for (const auto& [line, from] : lines)
            for (const auto f : list)
                if (f != from)
                    add_cut(f, {faces[f].frame.to2d(line[0]), faces[f].frame.to2d(line[1])}, true);
    }
}

} // namespace

CutLines find_cut_lines(const Scene& scene, const std::vector<std::uint32_t>& welded, double tol,
                        double size) {
    CutLines lines;
    for (const auto& poly : scene.polygons)
        lines.faces.push_back(make_face(scene, poly, welded, tol));
    CutFinder finder(lines, tol, size);
    finder.add_contacts(touching_pairs(lines.faces, tol));
    finder.run_on(scene, welded);
    return lines;
}

} // namespace rad::imprinting
