// Contact imprinting: cut where other objects touch or cross a face into it (CGAL's
// constrained Delaunay triangulation in the face's plane), drop the regions hidden inside
// other geometry, and keep the edges conforming.
#include "../union_find.hpp"
#include "polygon2d.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/scene.hpp"
#include "weld.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>

namespace rad {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
constexpr std::uint32_t kNone = 0xFFFFFFFFu;
struct VertexInfo {
    std::uint32_t index = kNone; // the scene vertex, once known
};
struct FaceInfo {
    bool inside = false; // within the face's outline
    int region = -1;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<
    K, CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>>;
using CDT =
    CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                               CGAL::Exact_predicates_tag>;
using Point2 = K::Point_2;

// A face's plane and its own 2D coordinates (u, v, with u x v = the normal).
struct Frame {
    Vec3 origin, normal, u, v;
    double offset; // normal . x on the plane
    std::array<double, 2> to2d(const Vec3& p) const {
        const Vec3 d = p - origin;
        return {dot(d, u), dot(d, v)};
    }
    Vec3 to3d(double x, double y) const { return origin + u * x + v * y; }
};

struct Face {
    std::vector<Vec3> points;
    Frame frame;
    Box box;
    std::vector<std::uint32_t> welded; // sorted welded ids of its corners
    bool planar = false;
    double area = 0;
};

struct Segment {
    std::array<double, 2> a, b;
};

double cross2(const std::array<double, 2>& o, const std::array<double, 2>& a,
              const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

bool convex(const std::vector<std::array<double, 2>>& poly) {
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k)
        if (cross2(poly[k], poly[(k + 1) % n], poly[(k + 2) % n]) < 0) return false;
    return true;
}

// Cyrus-Beck: the part of segment s inside the convex, counter-clockwise polygon.
bool clip_to_convex(Segment& s, const std::vector<std::array<double, 2>>& poly) {
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

} // namespace

ImprintReport imprint_contacts(Scene& scene, double tolerance, const std::vector<bool>& turned) {
    ImprintReport report;
    const std::size_t n = scene.polygons.size();
    if (n < 2) return report;
    const double size = bounds(scene.vertices).diagonal();
    if (!(size > 0)) return report;
    const double tol = tolerance * size;
    const auto welded = weld_by_position(scene.vertices);

    std::vector<Face> faces(n);
    for (std::size_t f = 0; f < n; ++f) {
        auto& face = faces[f];
        const auto& poly = scene.polygons[f];
        for (auto v : poly.vertices) {
            face.points.push_back(scene.vertices[v]);
            face.welded.push_back(welded[v]);
        }
        std::sort(face.welded.begin(), face.welded.end());
        const Vec3 n2 = newell_normal(face.points);
        face.area = 0.5 * length(n2);
        if (face.points.size() < 3 || !(face.area > 0)) continue;
        face.frame.normal = normalized(n2);
        face.frame.origin = face.points[0];
        face.frame.u = orthogonal(face.frame.normal);
        face.frame.v = cross(face.frame.normal, face.frame.u);
        face.frame.offset = dot(face.frame.normal, face.frame.origin);
        face.planar = true;
        for (const auto& x : face.points)
            if (std::abs(dot(x - face.frame.origin, face.frame.normal)) > tol) face.planar = false;
        face.box = bounds(face.points);
    }

    // Candidate pairs: overlapping boxes (a sweep along x), not of one object.
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

    // The cut lines of every face. A cut parallel to a side of a convex face runs on to its
    // outline, and on across the coplanar faces it continues into (the tiles of one floor):
    // a rectangle cut by lines parallel to its sides stays rectangles, so regular grids.
    // Other cuts stay as they are (slanted lines run on would make thin cells); the regions
    // they bound are triangulated.
    std::vector<std::vector<Segment>> cuts(n);
    std::vector<std::vector<std::array<Vec3, 2>>> chords(n); // the run-on lines, in 3D
    std::vector<std::vector<std::array<double, 2>>> outlines(n);
    std::vector<char> is_convex(n, 0);
    for (std::size_t f = 0; f < n; ++f) {
        if (!faces[f].planar) continue;
        for (const auto& x : faces[f].points) outlines[f].push_back(faces[f].frame.to2d(x));
        is_convex[f] = convex(outlines[f]);
    }
    // `run_on`: a line run on from a coplanar neighbour (it need not reach in by itself).
    auto add_cut = [&](std::size_t f, Segment c, bool run_on) {
        const auto& outline2d = outlines[f];
        const double dx = c.b[0] - c.a[0], dy = c.b[1] - c.a[1];
        const double len = std::hypot(dx, dy);
        if (len <= tol) return;
        bool parallel = false;
        for (std::size_t k = 0; k < outline2d.size() && !parallel; ++k) {
            const auto& e0 = outline2d[k];
            const auto& e1 = outline2d[(k + 1) % outline2d.size()];
            const double ex = e1[0] - e0[0], ey = e1[1] - e0[1];
            parallel = std::abs(dx * ey - dy * ex) <= 1e-9 * len * std::hypot(ex, ey);
        }
        if (run_on && !(is_convex[f] && parallel)) return;
        // Only a contact that reaches into the face (by more than the tolerance) cuts it.
        if (!run_on) {
            if (is_convex[f] && !clip_to_convex(c, outline2d)) return;
            if (std::hypot(c.b[0] - c.a[0], c.b[1] - c.a[1]) <= tol) return;
        }
        if (is_convex[f] && parallel) {
            const double reach = 4 * size / len;
            c = {{c.a[0] - reach * dx, c.a[1] - reach * dy},
                 {c.b[0] + reach * dx, c.b[1] + reach * dy}};
            if (!clip_to_convex(c, outline2d)) return;
        }
        if (std::hypot(c.b[0] - c.a[0], c.b[1] - c.a[1]) <= tol) return;
        // Along the outline already: nothing to cut.
        for (std::size_t k = 0; k < outline2d.size(); ++k) {
            const auto& e0 = outline2d[k];
            const auto& e1 = outline2d[(k + 1) % outline2d.size()];
            const double edge = std::hypot(e1[0] - e0[0], e1[1] - e0[1]);
            if (std::abs(cross2(e0, e1, c.a)) <= tol * edge &&
                std::abs(cross2(e0, e1, c.b)) <= tol * edge)
                return;
        }
        cuts[f].push_back(c);
        if (is_convex[f] && parallel)
            chords[f].push_back(
                {faces[f].frame.to3d(c.a[0], c.a[1]), faces[f].frame.to3d(c.b[0], c.b[1])});
    };
    for (std::size_t f = 0; f < n; ++f) {
        if (!faces[f].planar) continue;
        for (const auto q : touching[f]) {
            if (faces[q].area == 0) continue;
            Segment s;
            std::vector<Segment> found;
            if (contact(faces[f], faces[q], tol, s, found)) found.push_back(s);
            for (const auto& c : found) add_cut(f, c, false);
        }
    }
    // Coplanar faces sharing an edge (welded) form one surface; its run-on lines cross all.
    {
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
                    std::abs(g.frame.offset - faces[f].frame.offset) <= tol)
                    surfaces.unite(f, it->second);
            }
        }
        std::map<std::size_t, std::vector<std::size_t>> members;
        for (std::size_t f = 0; f < n; ++f)
            if (faces[f].planar) members[surfaces.find(f)].push_back(f);
        for (const auto& [root, list] : members) {
            if (list.size() < 2) continue;
            // Each line runs on into the others, not back into its own face: cut there
            // already, run on again it would be re-clipped a rounding error away (a second,
            // near-duplicate point on the outline).
            std::vector<std::pair<std::array<Vec3, 2>, std::size_t>> lines;
            for (const auto f : list)
                for (const auto& chord : chords[f]) lines.emplace_back(chord, f);
            for (const auto& [line, from] : lines)
                for (const auto f : list)
                    if (f != from)
                        add_cut(f, {faces[f].frame.to2d(line[0]), faces[f].frame.to2d(line[1])},
                                true);
        }
    }

    // Rays over the scene as written decide which regions are hidden.
    if (std::all_of(cuts.begin(), cuts.end(), [](const auto& c) { return c.empty(); }))
        return report;
    // Which way a face points counts as the orientation checks would fix it, so that a scene
    // whose walls face out does not make everything inside it look hidden.
    auto facing = [&] {
        Scene fixed = scene;
        for (std::size_t f = 0; f < n && f < turned.size(); ++f)
            if (turned[f])
                std::reverse(fixed.polygons[f].vertices.begin(), fixed.polygons[f].vertices.end());
        return face_triangles(fixed);
    };
    const RayScene rays(facing());

    // Points added on an original edge are shared by every face along that edge.
    struct EdgePoint {
        double t;
        std::uint32_t vertex;
    };
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<EdgePoint>> edge_points;
    auto edge_vertex = [&](std::uint32_t wa, std::uint32_t wb, const Vec3& a, const Vec3& b,
                           const Vec3& x) {
        const bool flip = wa > wb;
        const auto key = flip ? std::make_pair(wb, wa) : std::make_pair(wa, wb);
        const Vec3 from = flip ? b : a, to = flip ? a : b;
        const double len = length(to - from);
        const double t = dot(x - from, to - from) / (len * len);
        auto& list = edge_points[key];
        for (const auto& e : list)
            if (std::abs(e.t - t) * len <= tol) return e.vertex;
        const auto index = static_cast<std::uint32_t>(scene.vertices.size());
        scene.vertices.push_back(from + (to - from) * t);
        list.push_back({t, index});
        return index;
    };

    std::vector<std::vector<Polygon>> out(n); // what each face becomes, in face order
    std::vector<char> replaced(n, 0);
    for (std::size_t f = 0; f < n; ++f) {
        if (cuts[f].empty()) continue;
        const auto& p = faces[f];
        const auto& poly = scene.polygons[f];
        CDT cdt;
        std::vector<CDT::Vertex_handle> corner;
        std::vector<std::array<double, 2>> outline2d;
        for (std::size_t k = 0; k < p.points.size(); ++k) {
            const auto xy = p.frame.to2d(p.points[k]);
            outline2d.push_back(xy);
            corner.push_back(cdt.insert(Point2(xy[0], xy[1])));
            corner.back()->info().index = poly.vertices[k];
        }
        // Cut points closer than the tolerance to a corner or an earlier point are that point;
        // those on the outline are put exactly on it, and the outline is constrained through
        // them (a point a hair inside would leave a sliver between it and the outline).
        std::vector<CDT::Vertex_handle> known(corner);
        std::vector<std::vector<std::pair<double, CDT::Vertex_handle>>> on_edge(corner.size());
        auto snap = [&](std::array<double, 2> xy) {
            for (const auto& h : known)
                if (std::hypot(h->point().x() - xy[0], h->point().y() - xy[1]) <= tol) return h;
            std::size_t edge = corner.size();
            double t = 0;
            for (std::size_t k = 0; k < outline2d.size() && edge == corner.size(); ++k) {
                const auto& e0 = outline2d[k];
                const auto& e1 = outline2d[(k + 1) % outline2d.size()];
                const double ex = e1[0] - e0[0], ey = e1[1] - e0[1];
                const double len2 = ex * ex + ey * ey;
                if (!(len2 > 0)) continue;
                t = ((xy[0] - e0[0]) * ex + (xy[1] - e0[1]) * ey) / len2;
                if (t <= 0 || t >= 1 || std::abs(cross2(e0, e1, xy)) > tol * std::sqrt(len2))
                    continue;
                xy = {e0[0] + t * ex, e0[1] + t * ey};
                edge = k;
            }
            known.push_back(cdt.insert(Point2(xy[0], xy[1])));
            if (edge < corner.size()) on_edge[edge].emplace_back(t, known.back());
            return known.back();
        };
        std::vector<std::pair<CDT::Vertex_handle, CDT::Vertex_handle>> cut_edges;
        for (const auto& c : cuts[f]) {
            const auto a = snap(c.a), b = snap(c.b);
            if (a != b) cut_edges.emplace_back(a, b);
        }
        for (std::size_t k = 0; k < corner.size(); ++k) {
            auto& points = on_edge[k];
            std::sort(points.begin(), points.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
            auto from = corner[k];
            for (const auto& [t, h] : points) {
                if (h != from) cdt.insert_constraint(from, h);
                from = h;
            }
            if (from != corner[(k + 1) % corner.size()])
                cdt.insert_constraint(from, corner[(k + 1) % corner.size()]);
        }
        for (const auto& [a, b] : cut_edges) cdt.insert_constraint(a, b);
        for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
            const auto c = CGAL::centroid(fh->vertex(0)->point(), fh->vertex(1)->point(),
                                          fh->vertex(2)->point());
            fh->info().inside = point_in_polygon({c.x(), c.y()}, outline2d);
        }
        // Regions: faces reached without crossing a constraint.
        int regions = 0;
        std::vector<double> region_area;
        std::vector<CDT::Face_handle> region_seed;
        for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
            if (!fh->info().inside || fh->info().region >= 0) continue;
            std::queue<CDT::Face_handle> queue;
            fh->info().region = regions;
            queue.push(fh);
            region_area.push_back(0);
            region_seed.push_back(fh);
            double best = 0;
            while (!queue.empty()) {
                const auto g = queue.front();
                queue.pop();
                const double a = std::abs(CGAL::area(g->vertex(0)->point(), g->vertex(1)->point(),
                                                     g->vertex(2)->point()));
                region_area.back() += a;
                if (a > best) best = a, region_seed.back() = g;
                for (int e = 0; e < 3; ++e) {
                    const auto h = g->neighbor(e);
                    if (cdt.is_infinite(h) || g->is_constrained(e) || !h->info().inside ||
                        h->info().region >= 0)
                        continue;
                    h->info().region = regions;
                    queue.push(h);
                }
            }
            ++regions;
        }
        // A region is hidden when, from just above its largest triangle, most of what the
        // rays meet are backs (inside an object, under a block, behind a wall).
        std::vector<char> hidden(regions, 0);
        const double lift = std::max(2 * rays.epsilon(), 100 * tol);
        for (int r = 0; r < regions; ++r) {
            const auto g = region_seed[r];
            const auto c =
                CGAL::centroid(g->vertex(0)->point(), g->vertex(1)->point(), g->vertex(2)->point());
            const Vec3 front =
                f < turned.size() && turned[f] ? p.frame.normal * -1.0 : p.frame.normal;
            const Vec3 from = p.frame.to3d(c.x(), c.y()) + front * lift;
            const Vec3 tu = p.frame.u, tv = p.frame.v;
            int hits = 0, backs = 0;
            const int count = 64;
            for (int k = 0; k < count; ++k) {
                const double u = (k + 0.5) / count, w = std::fmod(k * 0.6180339887498949, 1.0);
                const auto hit = rays.trace(from, cosine_direction(front, tu, tv, u, w));
                if (hit.patch < 0) continue;
                ++hits;
                backs += !hit.front;
            }
            hidden[r] = hits > 0 && sees_mostly_backs(double(hits) / count, double(backs) / hits);
        }
        // The new vertices: corners keep theirs; points on the outline are shared along its
        // edges; the rest are new.
        for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
            if (v->info().index != kNone) continue;
            const std::array<double, 2> xy{v->point().x(), v->point().y()};
            const Vec3 x = p.frame.to3d(xy[0], xy[1]);
            for (std::size_t k = 0; k < outline2d.size() && v->info().index == kNone; ++k) {
                const std::size_t l = (k + 1) % outline2d.size();
                const double len = std::hypot(outline2d[l][0] - outline2d[k][0],
                                              outline2d[l][1] - outline2d[k][1]);
                if (std::abs(cross2(outline2d[k], outline2d[l], xy)) <= tol * len)
                    v->info().index =
                        edge_vertex(welded[poly.vertices[k]], welded[poly.vertices[l]], p.points[k],
                                    p.points[l], x);
            }
            if (v->info().index == kNone) {
                v->info().index = static_cast<std::uint32_t>(scene.vertices.size());
                scene.vertices.push_back(x);
            }
        }
        bool removed = false;
        auto piece = [&](std::vector<std::uint32_t> vertices) {
            // Points of the outline that are collinear up to rounding make triangles of no
            // area: they are not part of the face, and would count as degenerate input.
            std::vector<Vec3> corners;
            for (const auto v : vertices) corners.push_back(scene.vertices[v]);
            double longest = 0;
            for (std::size_t k = 0; k < corners.size(); ++k) {
                const Vec3 d = corners[(k + 1) % corners.size()] - corners[k];
                longest = std::max(longest, dot(d, d));
            }
            if (!(length(newell_normal(corners)) > 1e-9 * longest)) return;
            Polygon t;
            t.group = poly.group;
            t.material = poly.material;
            t.line = poly.line;
            t.vertices = std::move(vertices);
            out[f].push_back(std::move(t));
        };
        // A region whose outline is a convex triangle or quad stays one face (a plain
        // rectangle cut off a wall still becomes a regular grid); others are triangles.
        std::vector<std::map<std::uint32_t, std::uint32_t>> next_of(regions);
        std::vector<char> simple(regions, 1);
        for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
            if (!fh->info().inside) continue;
            const int r = fh->info().region;
            for (int e = 0; e < 3; ++e) {
                const auto h = fh->neighbor(e);
                if (!cdt.is_infinite(h) && h->info().inside && h->info().region == r) continue;
                const auto a = fh->vertex((e + 1) % 3)->info().index;
                const auto b = fh->vertex((e + 2) % 3)->info().index;
                if (!next_of[r].emplace(a, b).second) simple[r] = 0; // touches itself
            }
        }
        std::vector<std::vector<std::uint32_t>> outline_of(regions);
        for (int r = 0; r < regions; ++r) {
            if (!simple[r] || next_of[r].size() < 3 || next_of[r].size() > 4) {
                simple[r] = 0;
                continue;
            }
            auto& loop = outline_of[r];
            auto at = next_of[r].begin()->first;
            do {
                loop.push_back(at);
                const auto it = next_of[r].find(at);
                if (it == next_of[r].end()) break;
                at = it->second;
            } while (at != loop.front() && loop.size() <= next_of[r].size());
            std::vector<std::array<double, 2>> xy;
            for (const auto v : loop) xy.push_back(p.frame.to2d(scene.vertices[v]));
            simple[r] = loop.size() == next_of[r].size() && at == loop.front() && convex(xy);
        }
        for (int r = 0; r < regions; ++r)
            if (!hidden[r] && simple[r]) piece(outline_of[r]);
        for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
            if (!fh->info().inside) continue;
            const int r = fh->info().region;
            if (hidden[r] || simple[r]) continue;
            piece({fh->vertex(0)->info().index, fh->vertex(1)->info().index,
                   fh->vertex(2)->info().index});
        }
        // A hidden region wholly bounded by contact lines is a footprint (under a block, a
        // beam's end in a wall); one that reaches the face's own outline hides part of it.
        std::vector<char> reaches_outline(regions, 0);
        for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
            if (!fh->info().inside) continue;
            for (int e = 0; e < 3; ++e) {
                const auto h = fh->neighbor(e);
                if (cdt.is_infinite(h) || !h->info().inside) reaches_outline[fh->info().region] = 1;
            }
        }
        for (int r = 0; r < regions; ++r)
            if (hidden[r]) {
                ++report.regions_removed;
                report.area_removed += region_area[r];
                if (reaches_outline[r]) report.removed_by_group[poly.group] += region_area[r];
                removed = true;
            }
        if (removed) report.removed_lines.push_back(poly.line);
        replaced[f] = 1;
        ++report.faces_imprinted;
        report.area_imprinted += p.area;
    }
    if (!report.faces_imprinted) return report;

    // The other faces get the points added on their edges, in order, so no T-vertex is left.
    for (std::size_t f = 0; f < n; ++f) {
        if (replaced[f]) continue;
        auto poly = scene.polygons[f];
        std::vector<std::uint32_t> with_points;
        for (std::size_t k = 0; k < poly.vertices.size(); ++k) {
            const auto a = poly.vertices[k], b = poly.vertices[(k + 1) % poly.vertices.size()];
            with_points.push_back(a);
            const auto wa = welded[a], wb = welded[b];
            const auto it =
                edge_points.find(wa < wb ? std::make_pair(wa, wb) : std::make_pair(wb, wa));
            if (it == edge_points.end()) continue;
            auto list = it->second;
            std::sort(list.begin(), list.end(),
                      [](const EdgePoint& x, const EdgePoint& y) { return x.t < y.t; });
            if (wa > wb) std::reverse(list.begin(), list.end());
            for (const auto& e : list)
                if (e.t > 0 && e.t < 1) with_points.push_back(e.vertex);
        }
        poly.vertices = std::move(with_points);
        out[f].push_back(std::move(poly));
    }
    std::vector<Polygon> polygons;
    for (auto& pieces : out)
        for (auto& piece : pieces) polygons.push_back(std::move(piece));
    scene.polygons = std::move(polygons);
    return report;
}

} // namespace rad
