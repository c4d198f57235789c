// Contact imprinting: cut where other objects touch or cross a face into it (CGAL's
// constrained Delaunay triangulation in the face's plane), drop the regions hidden inside
// other geometry, and keep the edges conforming.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/imprint/imprint_parts.hpp"
#include "mesh/imprint/imprint_views.hpp"
#include "mesh/load/weld.hpp"
#include "radiosity/rays.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>

namespace rad {

using namespace imprinting;

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

// A cut face: its outline and cut lines triangulated, the outline constrained through the
// cut points on it.
struct CutFace {
    CDT cdt;
    std::vector<CDT::Vertex_handle> corner;
    std::vector<XY> outline2d;
};

// The cut face's regions: triangles reached from each other without crossing a constraint.
struct Regions {
    int count = 0;
    std::vector<double> area;
    std::vector<CDT::Face_handle> seed; // the largest triangle of each
};

// Where a cut point goes: within the tolerance of a corner or an earlier point, that point;
// on the outline, exactly on it (a point a hair inside would leave a sliver between it and
// the outline), noted with its edge so the outline is constrained through it.
class CutPoints {
  public:
    CutPoints(CutFace& cut, double tol) : cut_(cut), tol_(tol), known_(cut.corner) {
        on_edge_.resize(cut.corner.size());
    }
    CDT::Vertex_handle snap(XY xy) {
        for (const auto& h : known_)
            if (std::hypot(h->point().x() - xy[0], h->point().y() - xy[1]) <= tol_) return h;
        const auto& outline2d = cut_.outline2d;
        std::size_t edge = cut_.corner.size();
        double t = 0;
        for (std::size_t k = 0; k < outline2d.size() && edge == cut_.corner.size(); ++k) {
            const auto& e0 = outline2d[k];
            const auto& e1 = outline2d[(k + 1) % outline2d.size()];
            const double ex = e1[0] - e0[0], ey = e1[1] - e0[1];
            const double len2 = ex * ex + ey * ey;
            if (!(len2 > 0)) continue;
            t = ((xy[0] - e0[0]) * ex + (xy[1] - e0[1]) * ey) / len2;
            if (t <= 0 || t >= 1 || std::abs(cross2(e0, e1, xy)) > tol_ * std::sqrt(len2)) continue;
            xy = {e0[0] + t * ex, e0[1] + t * ey};
            edge = k;
        }
        known_.push_back(cut_.cdt.insert(Point2(xy[0], xy[1])));
        if (edge < cut_.corner.size()) on_edge_[edge].emplace_back(t, known_.back());
        return known_.back();
    }
    // The outline constrained corner to corner through the points snapped onto it.
    void constrain_outline() {
        const auto& corner = cut_.corner;
        for (std::size_t k = 0; k < corner.size(); ++k) {
            auto& points = on_edge_[k];
            std::sort(points.begin(), points.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
            auto from = corner[k];
            for (const auto& [t, h] : points) {
                if (h != from) cut_.cdt.insert_constraint(from, h);
                from = h;
            }
            if (from != corner[(k + 1) % corner.size()])
                cut_.cdt.insert_constraint(from, corner[(k + 1) % corner.size()]);
        }
    }

  private:
    CutFace& cut_;
    double tol_;
    std::vector<CDT::Vertex_handle> known_;
    std::vector<std::vector<std::pair<double, CDT::Vertex_handle>>> on_edge_;
};

Regions find_regions(CDT& cdt) {
    Regions regions;
    for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
        if (!fh->info().inside || fh->info().region >= 0) continue;
        std::queue<CDT::Face_handle> queue;
        fh->info().region = regions.count;
        queue.push(fh);
        regions.area.push_back(0);
        regions.seed.push_back(fh);
        double best = 0;
        while (!queue.empty()) {
            const auto g = queue.front();
            queue.pop();
            const double a = std::abs(
                CGAL::area(g->vertex(0)->point(), g->vertex(1)->point(), g->vertex(2)->point()));
            regions.area.back() += a;
            if (a > best) best = a, regions.seed.back() = g;
            for (int e = 0; e < 3; ++e) {
                const auto h = g->neighbor(e);
                if (cdt.is_infinite(h) || g->is_constrained(e) || !h->info().inside ||
                    h->info().region >= 0)
                    continue;
                h->info().region = regions.count;
                queue.push(h);
            }
        }
        ++regions.count;
    }
    return regions;
}

// A region whose outline is a convex triangle or quad stays one face (a plain rectangle cut
// off a wall still becomes a regular grid): its outline, counter-clockwise; empty for others.
std::vector<std::vector<std::uint32_t>>
simple_outlines(const CDT& cdt, int count, const Frame& frame, const std::vector<Vec3>& vertices) {
    std::vector<std::map<std::uint32_t, std::uint32_t>> next_of(count);
    std::vector<char> simple(count, 1);
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
    std::vector<std::vector<std::uint32_t>> outline_of(count);
    for (int r = 0; r < count; ++r) {
        if (!simple[r] || next_of[r].size() < 3 || next_of[r].size() > 4) continue;
        std::vector<std::uint32_t> loop;
        auto at = next_of[r].begin()->first;
        do {
            loop.push_back(at);
            const auto it = next_of[r].find(at);
            if (it == next_of[r].end()) break;
            at = it->second;
        } while (at != loop.front() && loop.size() <= next_of[r].size());
        std::vector<XY> xy;
        for (const auto v : loop) xy.push_back(frame.to2d(vertices[v]));
        if (loop.size() == next_of[r].size() && at == loop.front() && convex(xy))
            outline_of[r] = std::move(loop);
    }
    return outline_of;
}

// Which regions are bounded mostly by the face's own outline, not by contact lines: the
// strip under a wall standing across a floor reaches the floor's outline only at its ends.
std::vector<char> mostly_outline(const CDT& cdt, int count) {
    std::vector<double> outline(count, 0), boundary(count, 0);
    for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
        if (!fh->info().inside) continue;
        const int r = fh->info().region;
        for (int e = 0; e < 3; ++e) {
            const auto h = fh->neighbor(e);
            const bool out = cdt.is_infinite(h) || !h->info().inside;
            if (!out && h->info().region == r) continue;
            const auto& a = fh->vertex((e + 1) % 3)->point();
            const auto& b = fh->vertex((e + 2) % 3)->point();
            const double length =
                std::hypot(CGAL::to_double(b.x() - a.x()), CGAL::to_double(b.y() - a.y()));
            boundary[r] += length;
            if (out) outline[r] += length;
        }
    }
    std::vector<char> mostly(count, 0);
    for (int r = 0; r < count; ++r) mostly[r] = outline[r] > 0.5 * boundary[r];
    return mostly;
}

// Whether region r (of a face's regions, each seen from the same side) sees mostly backs
// that set it apart from the rest of its face. The backs of a surface count when
// - it closes around r and clearly not around another region: a block standing on the face,
//   a wall it runs through (a vault or a room over the whole face does not count, whichever
//   way it was drawn);
// - it is a room that clearly does not close around r, but does around another region, or
//   is closed: r is outside it;
// - it is not a closed object, and another region sees its front (at most a quarter as many
//   rays on its back), or, unless it is a room, at most a quarter as many of its backs as r:
//   a wall made of two sheets over a strip of floor, a cavity behind a game map's wall, a
//   baseboard standing against a wall (the backs of a ceiling below a floor drawn facing
//   down, of a vault near its mouth, or of a room drawn facing out, seen alike from all of
//   the face or from nowhere else, do not count).
// A closed object's backs seen from outside it say only that it was drawn inside out.
bool behind_object(const SurfaceViews& surfaces, const std::vector<SurfaceViews::View>& views,
                   std::size_t r, const Vec3& from, const Frame& plane, double gap) {
    const auto& view = views[r];
    const auto any = [&](auto&& test) { return std::any_of(views.begin(), views.end(), test); };
    const auto counts = [&](std::uint32_t s) {
        // Around the region and not around the rest: an object over a footprint, unless
        // the scene's open side reaches in through its openings (a tunnel's floor under a
        // vault drawn facing out, open at its ends, is no footprint).
        if (view.inside(s))
            return any([&](const auto& other) { return other.outside(s); }) &&
                   !surfaces.open_to_outside(s, from, plane.normal, dot(plane.normal, plane.origin),
                                             gap);
        const bool enclosing = any([&](const auto& other) { return other.inside(s); });
        const bool closes = enclosing || surfaces.closed(s);
        if (surfaces.room(s) && view.outside(s) && closes) return true;
        if (!surfaces.room(s) && surfaces.closed(s)) return false;
        // Another region sees its front; or, for an object, far fewer of its backs.
        return any([&](const auto& other) {
            const int fronts = other.fronts_of(s), other_backs = other.backs_of(s);
            return (fronts > 0 && 4 * other_backs <= fronts) ||
                   (!surfaces.room(s) && 4 * other_backs <= view.backs_of(s));
        });
    };
    int backs = 0;
    for (const auto& [surface, count] : view.backs)
        if (counts(surface)) backs += count;
    return view.mostly(backs);
}

class Imprinter {
  public:
    Imprinter(Scene& scene, double tol, double gap, const std::vector<bool>& turned,
              std::vector<std::uint32_t> welded, CutLines lines)
        : scene_(scene), tol_(tol), gap_(std::max(gap, 100 * tol)), turned_(turned),
          welded_(std::move(welded)), lines_(std::move(lines)), views_(scene, turned, welded_),
          replaced_(scene.polygons.size(), 0) {}
    void cut_faces() {
        for (const auto& [f, cuts] : lines_.cuts) cut_face(f);
    }
    void finish(); // the other faces get the points put on their edges
    ImprintReport report;

  private:
    void cut_face(std::size_t f);
    void triangulate_cuts(std::size_t f, CutFace& cut);
    std::vector<char> hidden_regions(std::size_t f, const Regions& regions) const;
    void number_vertices(std::size_t f, CutFace& cut);
    std::uint32_t edge_vertex(std::uint32_t wa, std::uint32_t wb, const Vec3& a, const Vec3& b,
                              const Vec3& x);
    void add_piece(std::size_t f, std::vector<std::uint32_t> vertices);
    void add_edge_points(Polygon& poly) const;
    void place_pieces();
    void emit_pieces(std::size_t f, const CutFace& cut, const Regions& regions,
                     const std::vector<char>& hidden);

    // Points added on an original edge are shared by every face along that edge.
    struct EdgePoint {
        double t;
        std::uint32_t vertex;
    };

    Scene& scene_;
    double tol_;
    double gap_; // how far from a face an object's open edges may stand and close on it
    const std::vector<bool>& turned_;
    std::vector<std::uint32_t> welded_;
    CutLines lines_;
    // Which way a face points counts as the orientation checks would fix it, so that a scene
    // whose walls face out does not make everything inside it look hidden.
    SurfaceViews views_;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<EdgePoint>> edge_points_;
    std::map<std::size_t, std::vector<Polygon>> out_; // what each cut face becomes
    std::vector<char> replaced_;
};

void Imprinter::triangulate_cuts(std::size_t f, CutFace& cut) {
    const auto& p = lines_.faces.at(f);
    const auto& poly = scene_.polygons[f];
    for (std::size_t k = 0; k < p.points.size(); ++k) {
        const auto xy = p.frame.to2d(p.points[k]);
        cut.outline2d.push_back(xy);
        cut.corner.push_back(cut.cdt.insert(Point2(xy[0], xy[1])));
        cut.corner.back()->info().index = poly.vertices[k];
    }
    CutPoints points(cut, tol_);
    std::vector<std::pair<CDT::Vertex_handle, CDT::Vertex_handle>> cut_edges;
    for (const auto& c : lines_.cuts.at(f)) {
        const auto a = points.snap(c.a), b = points.snap(c.b);
        if (a != b) cut_edges.emplace_back(a, b);
    }
    points.constrain_outline();
    for (const auto& [a, b] : cut_edges) cut.cdt.insert_constraint(a, b);
    for (auto fh = cut.cdt.finite_faces_begin(); fh != cut.cdt.finite_faces_end(); ++fh) {
        const auto c =
            CGAL::centroid(fh->vertex(0)->point(), fh->vertex(1)->point(), fh->vertex(2)->point());
        fh->info().inside = point_in_polygon({c.x(), c.y()}, cut.outline2d);
    }
}

// A region is hidden when, from just off its largest triangle on either side (the face may
// point either way), it sees mostly the backs of an object that the rest of the face does not
// (behind_object).
std::vector<char> Imprinter::hidden_regions(std::size_t f, const Regions& regions) const {
    const auto& p = lines_.faces.at(f);
    std::vector<char> hidden(regions.count, 0);
    const double lift = std::max(2 * views_.epsilon(), 100 * tol_);
    const bool turned = f < turned_.size() && turned_[f];
    for (const Vec3& side : {p.frame.normal, p.frame.normal * -1.0}) {
        std::vector<Vec3> from;
        for (int r = 0; r < regions.count; ++r) {
            const auto g = regions.seed[r];
            const auto c =
                CGAL::centroid(g->vertex(0)->point(), g->vertex(1)->point(), g->vertex(2)->point());
            from.push_back(p.frame.to3d(c.x(), c.y()) + side * lift);
        }
        std::vector<SurfaceViews::View> views(regions.count);
        tbb::parallel_for(0, regions.count, [&](int r) {
            views[r] = views_.view(from[r], side, p.frame.u, p.frame.v);
        });
        // Only backs can hide a region: where no region sees mostly backs of anything, the
        // rays need not be followed to the end.
        const bool some_backs = std::any_of(views.begin(), views.end(), [](const auto& view) {
            int backs = 0;
            for (const auto& [surface, count] : view.backs) backs += count;
            return view.mostly(backs);
        });
        if (!some_backs) continue;
        std::vector<std::uint32_t> seen_backs; // the surfaces whose backs any region sees
        for (const auto& view : views)
            for (const auto& [surface, count] : view.backs) seen_backs.push_back(surface);
        std::sort(seen_backs.begin(), seen_backs.end());
        seen_backs.erase(std::unique(seen_backs.begin(), seen_backs.end()), seen_backs.end());
        tbb::parallel_for(0, regions.count, [&](int r) {
            views_.add_parity(views[r], from[r], side, p.frame.u, p.frame.v, seen_backs);
        });
        // Behind the face, inside its own closed object (a sphere's inside, where a water
        // line running through it shows its underside), nothing is seen.
        const bool back = (dot(side, p.frame.normal) > 0) == turned;
        const auto own = views_.surface_of(f);
        for (int r = 0; r < regions.count; ++r)
            if (!(back && views[r].inside(own)))
                hidden[r] |= behind_object(views_, views, std::size_t(r), from[r], p.frame, gap_);
    }
    return hidden;
}

std::uint32_t Imprinter::edge_vertex(std::uint32_t wa, std::uint32_t wb, const Vec3& a,
                                     const Vec3& b, const Vec3& x) {
    const bool flip = wa > wb;
    const auto key = flip ? std::make_pair(wb, wa) : std::make_pair(wa, wb);
    const Vec3 from = flip ? b : a, to = flip ? a : b;
    const double len = length(to - from);
    const double t = dot(x - from, to - from) / (len * len);
    auto& list = edge_points_[key];
    for (const auto& e : list)
        if (std::abs(e.t - t) * len <= tol_) return e.vertex;
    const auto index = static_cast<std::uint32_t>(scene_.vertices.size());
    scene_.vertices.push_back(from + (to - from) * t);
    list.push_back({t, index});
    return index;
}

// The new vertices: corners keep theirs; points on the outline are shared along its edges;
// the rest are new.
void Imprinter::number_vertices(std::size_t f, CutFace& cut) {
    const auto& p = lines_.faces.at(f);
    const auto& poly = scene_.polygons[f];
    const auto& outline2d = cut.outline2d;
    for (auto v = cut.cdt.finite_vertices_begin(); v != cut.cdt.finite_vertices_end(); ++v) {
        if (v->info().index != kNone) continue;
        const XY xy{v->point().x(), v->point().y()};
        const Vec3 x = p.frame.to3d(xy[0], xy[1]);
        for (std::size_t k = 0; k < outline2d.size() && v->info().index == kNone; ++k) {
            const std::size_t l = (k + 1) % outline2d.size();
            const double len =
                std::hypot(outline2d[l][0] - outline2d[k][0], outline2d[l][1] - outline2d[k][1]);
            if (std::abs(cross2(outline2d[k], outline2d[l], xy)) <= tol_ * len)
                v->info().index = edge_vertex(welded_[poly.vertices[k]], welded_[poly.vertices[l]],
                                              p.points[k], p.points[l], x);
        }
        if (v->info().index == kNone) {
            v->info().index = static_cast<std::uint32_t>(scene_.vertices.size());
            scene_.vertices.push_back(x);
        }
    }
}

void Imprinter::add_piece(std::size_t f, std::vector<std::uint32_t> vertices) {
    // Points of the outline that are collinear up to rounding make triangles of no area:
    // they are not part of the face, and would count as degenerate input.
    std::vector<Vec3> corners;
    for (const auto v : vertices) corners.push_back(scene_.vertices[v]);
    double longest = 0;
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const Vec3 d = corners[(k + 1) % corners.size()] - corners[k];
        longest = std::max(longest, dot(d, d));
    }
    if (!(length(newell_normal(corners)) > 1e-9 * longest)) return;
    const auto& poly = scene_.polygons[f];
    Polygon t;
    t.group = poly.group;
    t.material = poly.material;
    t.line = poly.line;
    t.vertices = std::move(vertices);
    out_[f].push_back(std::move(t));
}

void Imprinter::emit_pieces(std::size_t f, const CutFace& cut, const Regions& regions,
                            const std::vector<char>& hidden) {
    const auto outline_of =
        simple_outlines(cut.cdt, regions.count, lines_.faces.at(f).frame, scene_.vertices);
    for (int r = 0; r < regions.count; ++r)
        if (!hidden[r] && !outline_of[r].empty()) add_piece(f, outline_of[r]);
    for (auto fh = cut.cdt.finite_faces_begin(); fh != cut.cdt.finite_faces_end(); ++fh) {
        if (!fh->info().inside) continue;
        const int r = fh->info().region;
        if (hidden[r] || !outline_of[r].empty()) continue;
        add_piece(f, {fh->vertex(0)->info().index, fh->vertex(1)->info().index,
                      fh->vertex(2)->info().index});
    }
}

void Imprinter::cut_face(std::size_t f) {
    CutFace cut;
    triangulate_cuts(f, cut);
    const auto regions = find_regions(cut.cdt);
    const auto hidden = hidden_regions(f, regions);
    number_vertices(f, cut);
    emit_pieces(f, cut, regions, hidden);
    // A hidden region bounded by contact lines is a footprint (under a block, a beam's end in
    // a wall, under a wall across a floor); one bounded mostly by the face's own outline hides
    // part of the face itself.
    const auto outline_bounded = mostly_outline(cut.cdt, regions.count);
    const auto& poly = scene_.polygons[f];
    bool removed = false;
    for (int r = 0; r < regions.count; ++r)
        if (hidden[r]) {
            ++report.regions_removed;
            report.area_removed += regions.area[r];
            if (outline_bounded[r]) report.removed_by_group[poly.group] += regions.area[r];
            removed = true;
        }
    if (removed) report.removed_lines.push_back(poly.line);
    replaced_[f] = 1;
    ++report.faces_imprinted;
    report.area_imprinted += lines_.faces.at(f).area;
}

void Imprinter::finish() {
    std::vector<char> on_cut_edge(
        welded_.empty() ? 0 : *std::max_element(welded_.begin(), welded_.end()) + 1, 0);
    for (const auto& [edge, points] : edge_points_)
        on_cut_edge[edge.first] = on_cut_edge[edge.second] = 1;
    auto& polygons = scene_.polygons;
    for (std::size_t f = 0; f < polygons.size(); ++f) {
        if (replaced_[f]) continue;
        auto& poly = polygons[f];
        const bool touched = std::any_of(poly.vertices.begin(), poly.vertices.end(),
                                         [&](std::uint32_t v) { return on_cut_edge[welded_[v]]; });
        if (touched) add_edge_points(poly);
    }
    place_pieces();
}

// Each cut face becomes its pieces. In place where every face's polygons land at or after its
// own index (moved from the last face down, none is overwritten before it has moved): a
// second vector of every face would add its size to a large scene's peak memory.
void Imprinter::place_pieces() {
    auto& polygons = scene_.polygons;
    const std::size_t n = polygons.size();
    auto pieces_of = [&](std::size_t f) -> std::vector<Polygon>* {
        const auto it = out_.find(f);
        return it == out_.end() ? nullptr : &it->second;
    };
    std::vector<std::size_t> start(n + 1, 0);
    bool in_place = true;
    for (std::size_t f = 0; f < n; ++f) {
        const auto count = !replaced_[f] ? 1 : pieces_of(f) ? pieces_of(f)->size() : 0;
        if (count > 0 && start[f] < f) in_place = false;
        start[f + 1] = start[f] + count;
    }
    if (!in_place) {
        std::vector<Polygon> out;
        out.reserve(start[n]);
        for (std::size_t f = 0; f < n; ++f)
            if (!replaced_[f])
                out.push_back(std::move(polygons[f]));
            else if (auto* pieces = pieces_of(f))
                for (auto& piece : *pieces) out.push_back(std::move(piece));
        polygons = std::move(out);
        return;
    }
    polygons.resize(std::max(n, start[n]));
    for (std::size_t f = n; f-- > 0;) {
        if (!replaced_[f]) {
            if (start[f] != f) polygons[start[f]] = std::move(polygons[f]);
        } else if (auto* pieces = pieces_of(f)) {
            for (std::size_t k = 0; k < pieces->size(); ++k)
                polygons[start[f] + k] = std::move((*pieces)[k]);
        }
    }
    polygons.resize(start[n]);
}

// The points other faces' cuts put on this face's edges, in order along each edge.
void Imprinter::add_edge_points(Polygon& poly) const {
    std::vector<std::uint32_t> with_points;
    for (std::size_t k = 0; k < poly.vertices.size(); ++k) {
        const auto a = poly.vertices[k], b = poly.vertices[(k + 1) % poly.vertices.size()];
        with_points.push_back(a);
        const auto wa = welded_[a], wb = welded_[b];
        const auto it =
            edge_points_.find(wa < wb ? std::make_pair(wa, wb) : std::make_pair(wb, wa));
        if (it == edge_points_.end()) continue;
        auto list = it->second;
        std::sort(list.begin(), list.end(),
                  [](const EdgePoint& x, const EdgePoint& y) { return x.t < y.t; });
        if (wa > wb) std::reverse(list.begin(), list.end());
        for (const auto& e : list)
            if (e.t > 0 && e.t < 1) with_points.push_back(e.vertex);
    }
    poly.vertices = std::move(with_points);
}

} // namespace

ImprintReport imprint_contacts(Scene& scene, double tolerance, const std::vector<bool>& turned,
                               double gap) {
    if (scene.polygons.size() < 2) return {};
    const double size = bounds(scene.vertices).diagonal();
    if (!(size > 0)) return {};
    const double tol = tolerance * size;
    auto welded = weld_by_position(scene.vertices);
    auto lines = find_cut_lines(scene, welded, tol, gap * size, size);
    scene.contact_lines.insert(scene.contact_lines.end(), lines.contacts.begin(),
                               lines.contacts.end());
    // Rays over the scene as written decide which regions are hidden.
    if (lines.cuts.empty()) return {};
    Imprinter imprinter(scene, tol, gap * size, turned, std::move(welded), std::move(lines));
    imprinter.cut_faces();
    if (imprinter.report.faces_imprinted) imprinter.finish();
    return imprinter.report;
}

} // namespace rad
