// Pass 4 of mesh_surfaces: a region's grid of quads, and the triangles of the band between the
// grid and the outline.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/geometry/square_index.hpp"
#include "mesh/regions/regions.hpp"

#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace rad::surfaces {

namespace {

// The band's triangulation, refined for shape (CGAL's Delaunay mesher) without splitting its
// constrained edges: those are shared with the grid's quads and with other regions.
using BandFb = CGAL::Delaunay_mesh_face_base_2<K, CGAL::Constrained_triangulation_face_base_2<K>>;
using BandCDT =
    CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, BandFb>,
                                               CGAL::Exact_predicates_tag>;

// CGAL's size and angle criteria, plus: a triangle whose aspect (longest edge over shortest
// height) is over 3 is bad. An angle bound alone lets obtuse triangles of 25-30 degree corners
// through, whose aspect reaches 5. But a triangle whose circumcircle is under a fifth of a cell
// across is left as it is, however it is shaped: refining it would add its circumcentre, under a
// tenth of a cell from its corners. Beside the outline's short pieces (a column's round top of 40
// sides, a notch) that refinement went on down to the pieces' size: dozens of specks where a few
// triangles, thin or not, cover the same ground. Nor is a triangle refined for its shape whose
// circumcentre would land under a tenth of a cell from a point already there (one of zdm2's round
// caps got five specks of three such centres).
struct BandCriteria : CGAL::Delaunay_mesh_size_criteria_2<BandCDT> {
    using Base = CGAL::Delaunay_mesh_size_criteria_2<BandCDT>;
    BandCriteria(double cell, const BandCDT& cdt)
        : Base(0.125, cell), smallest_circumradius_(cell / 10), cdt_(&cdt) {}
    struct Is_bad : Base::Is_bad {
        Is_bad(double aspect_bound, double size_bound, const BandCDT::Geom_traits& geometry,
               double smallest_circumradius, const BandCDT* triangulation)
            : Base::Is_bad(aspect_bound, size_bound, geometry),
              smallest_circumradius_squared(smallest_circumradius * smallest_circumradius),
              cdt(triangulation) {}
        CGAL::Mesh_2::Face_badness operator()(const Quality q) const {
            return Base::Is_bad::operator()(q);
        }
        CGAL::Mesh_2::Face_badness operator()(const BandCDT::Face_handle& face, Quality& q) const {
            const auto &a = face->vertex(0)->point(), &b = face->vertex(1)->point(),
                       &c = face->vertex(2)->point();
            const double ab = CGAL::squared_distance(a, b), bc = CGAL::squared_distance(b, c),
                         ca = CGAL::squared_distance(c, a);
            const double twice_area = std::abs(2 * CGAL::area(a, b, c));
            // The circumradius R = |ab| |bc| |ca| / (4 area): R^2 < r^2 without roots.
            if (twice_area > 0 &&
                ab * bc * ca < smallest_circumradius_squared * 4 * twice_area * twice_area) {
                q = Quality(1, 0); // not bad, and not in the queue's way
                return CGAL::Mesh_2::NOT_BAD;
            }
            auto badness = Base::Is_bad::operator()(face, q);
            if (badness == CGAL::Mesh_2::NOT_BAD) {
                const double longest = std::max({ab, bc, ca});
                const double aspect = twice_area > 0 ? longest / twice_area : 1e300;
                if (aspect <= kMaxAspect) return CGAL::Mesh_2::NOT_BAD;
                q.first = std::min(q.first,
                                   0.999 * this->B * (kMaxAspect / aspect) * (kMaxAspect / aspect));
                badness = CGAL::Mesh_2::BAD;
            }
            // A triangle too large is refined wherever its circumcentre lands.
            if (badness == CGAL::Mesh_2::BAD && circumcentre_near_a_point(a, b, c)) {
                q = Quality(1, 0);
                return CGAL::Mesh_2::NOT_BAD;
            }
            return badness;
        }
        // Where the circumcentre would land under a tenth of a cell from a point already there
        // (hidden from the triangle behind the outline, or a second centre of a rim whose
        // points are nearly on one circle), refining would make a speck.
        bool circumcentre_near_a_point(const Point2& a, const Point2& b, const Point2& c) const {
            if (CGAL::collinear(a, b, c)) return false;
            const Point2 centre = CGAL::circumcenter(a, b, c);
            const auto f = cdt->locate(centre);
            if (cdt->is_infinite(f)) return false;
            for (int k = 0; k < 3; ++k)
                if (CGAL::squared_distance(f->vertex(k)->point(), centre) <
                    smallest_circumradius_squared)
                    return true;
            return false;
        }
        double smallest_circumradius_squared;
        const BandCDT* cdt;
    };
    Is_bad is_bad_object() const {
        return Is_bad(this->bound(), this->size_bound(), this->traits, smallest_circumradius_,
                      cdt_);
    }
    static constexpr double kMaxAspect = 3;
    double smallest_circumradius_; // of a triangle refined
    const BandCDT* cdt_;
};

// The grid over one region: which nodes lie on outline points, which are well inside, which
// cells are whole quads.
class RegionGrid {
  public:
    RegionGrid(const Region& region, const GridFrame& frame, const std::vector<XY>& outline_xy,
               const std::vector<std::uint32_t>& outline_ids, const Points& points,
               double tolerance)
        : region_(region), frame_(frame) {
        for (const auto& [a, b] : region.pieces)
            piece_xy_.push_back(
                {region.plane.to_2d(points.position[a]), region.plane.to_2d(points.position[b])});
        const double h = region.cell;
        nu_ =
            h > 0 ? std::max<std::size_t>(1, std::size_t(std::ceil(frame.length1 / h - 1e-9))) : 1;
        nv_ =
            h > 0 ? std::max<std::size_t>(1, std::size_t(std::ceil(frame.length2 / h - 1e-9))) : 1;
        du_ = frame.length1 / double(nu_);
        dv_ = frame.length2 / double(nv_);
        node_id_.assign((nu_ + 1) * (nv_ + 1), kNone);
        node_ok_.assign(node_id_.size(), false);
        blocked_.assign(nu_ * nv_, false);
        full_.assign(nu_ * nv_, false);
        const double snap = tolerance + 1e-6 * std::min(du_, dv_);
        for (std::size_t k = 0; k < outline_ids.size(); ++k)
            place_outline_point(outline_xy[k], outline_ids[k], snap);
    }
    std::size_t nu() const { return nu_; }
    std::size_t nv() const { return nv_; }
    XY node_xy(std::size_t i, std::size_t j) const {
        const double s = double(i) * du_, t = double(j) * dv_;
        return {frame_.origin[0] + frame_.e1[0] * s + frame_.e2[0] * t,
                frame_.origin[1] + frame_.e1[1] * s + frame_.e2[1] * t};
    }
    std::size_t node(std::size_t i, std::size_t j) const { return j * (nu_ + 1) + i; }
    std::size_t cell(std::size_t i, std::size_t j) const { return j * nu_ + i; }
    std::uint32_t& id(std::size_t i, std::size_t j) { return node_id_[node(i, j)]; }
    std::uint32_t id(std::size_t i, std::size_t j) const { return node_id_[node(i, j)]; }
    bool full(std::size_t i, std::size_t j) const { return full_[cell(i, j)]; }
    bool full_at(const XY& p) const {
        const auto [s, t] = frame_.local(p);
        const auto i = static_cast<long long>(std::floor(s / du_)),
                   j = static_cast<long long>(std::floor(t / dv_));
        if (i < 0 || j < 0 || i >= (long long)nu_ || j >= (long long)nv_) return false;
        return full_[cell(std::size_t(i), std::size_t(j))];
    }
    bool node_ok(std::size_t i, std::size_t j) const { return node_ok_[node(i, j)]; }
    // The cell is left to the band (its corners stay usable points of the band).
    void give_to_band(std::size_t i, std::size_t j) { full_[cell(i, j)] = false; }
    bool matched(std::size_t i, std::size_t j) const { return matched_.count(node(i, j)) > 0; }

    // Nodes off the outline are usable when inside and a third of a cell from the outline.
    void classify_nodes(const std::unordered_set<EdgeKey>& pieces) {
        const double margin = 0.3 * std::min(du_, dv_);
        index_pieces(margin);
        for (std::size_t j = 0; j <= nv_; ++j)
            for (std::size_t i = 0; i <= nu_; ++i)
                node_ok_[node(i, j)] = matched(i, j) || well_inside(node_xy(i, j), margin);
        for (std::size_t j = 0; j < nv_; ++j)
            for (std::size_t i = 0; i < nu_; ++i)
                full_[cell(i, j)] = cell_is_whole(i, j, pieces, margin);
    }

  private:
    void place_outline_point(const XY& p, std::uint32_t id, double snap) {
        const auto [s, t] = frame_.local(p);
        const double fi = s / du_, fj = t / dv_;
        const double ri = std::round(fi), rj = std::round(fj);
        const bool on_i = std::abs(fi - ri) * du_ < snap, on_j = std::abs(fj - rj) * dv_ < snap;
        auto block = [&](long long i, long long j) {
            if (i >= 0 && j >= 0 && i < (long long)nu_ && j < (long long)nv_)
                blocked_[cell(std::size_t(i), std::size_t(j))] = true;
        };
        const auto ii = static_cast<long long>(ri), jj = static_cast<long long>(rj);
        const auto fli = static_cast<long long>(std::floor(fi)),
                   flj = static_cast<long long>(std::floor(fj));
        if (on_i && on_j) {
            if (ii >= 0 && jj >= 0 && ii <= (long long)nu_ && jj <= (long long)nv_ &&
                !matched(std::size_t(ii), std::size_t(jj))) {
                node_id_[node(std::size_t(ii), std::size_t(jj))] = id;
                matched_.insert(node(std::size_t(ii), std::size_t(jj)));
            }
        } else if (on_i) {
            block(ii - 1, flj), block(ii, flj);
        } else if (on_j) {
            block(fli, jj - 1), block(fli, jj);
        } else {
            block(fli, flj);
        }
    }
    // The pieces in squares of a cell's side (or a quarter of the longest piece's box, where
    // pieces are longer than cells: a sliver region), each in every square its box grown by
    // `margin` touches: a point within `margin` of a piece finds it in its own square. (Trying
    // every piece for every node was quadratic: 145 s of rad-mesh for the Cornell box at 4e6
    // patches.)
    void index_pieces(double margin) {
        double longest = 0;
        for (const auto& [a, b] : piece_xy_)
            longest = std::max({longest, std::abs(a[0] - b[0]), std::abs(a[1] - b[1])});
        piece_index_ =
            SquareIndex(std::max({std::min(du_, dv_), (longest + 2 * margin) / 4, 1e-300}));
        for (std::size_t k = 0; k < piece_xy_.size(); ++k) {
            const auto& [a, b] = piece_xy_[k];
            piece_index_.insert({std::min(a[0], b[0]) - margin, std::min(a[1], b[1]) - margin},
                                {std::max(a[0], b[0]) + margin, std::max(a[1], b[1]) + margin},
                                static_cast<std::uint32_t>(k));
        }
        piece_index_.freeze();
    }
    bool well_inside(const XY& p, double margin) const {
        if (!region_.contains(Point2(p[0], p[1]))) return false;
        return !piece_index_.find_near(p, 0, [&](std::uint32_t k) {
            return segment_distance(p, piece_xy_[k][0], piece_xy_[k][1]) < margin;
        });
    }
    bool cell_is_whole(std::size_t i, std::size_t j, const std::unordered_set<EdgeKey>& pieces,
                       double margin) const {
        if (blocked_[cell(i, j)]) return false;
        const std::array<std::array<std::size_t, 2>, 4> c{
            {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
        for (const auto& [a, b] : c)
            if (!node_ok(a, b)) return false;
        const XY mid = node_xy(i, j), far = node_xy(i + 1, j + 1);
        if (!region_.contains(Point2((mid[0] + far[0]) / 2, (mid[1] + far[1]) / 2))) return false;
        for (int k = 0; k < 4; ++k) { // a side between two outline points lies on the outline
            const auto& p = c[k];
            const auto& q = c[(k + 1) % 4];
            if (!matched(p[0], p[1]) || !matched(q[0], q[1])) continue;
            if (pieces.count(edge_key(node_id_[node(p[0], p[1])], node_id_[node(q[0], q[1])])))
                continue;
            const XY a = node_xy(p[0], p[1]), b = node_xy(q[0], q[1]);
            if (!well_inside({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2}, margin)) return false;
        }
        return true;
    }

    const Region& region_;
    GridFrame frame_;
    std::vector<std::array<XY, 2>> piece_xy_; // the region's outline pieces in its plane
    SquareIndex piece_index_{1.0};            // of piece_xy_, by classify_nodes
    std::size_t nu_ = 1, nv_ = 1;
    double du_ = 1, dv_ = 1;
    std::vector<std::uint32_t> node_id_;
    std::vector<bool> node_ok_, blocked_, full_;
    std::unordered_set<std::size_t> matched_;
};

void emit(const Region& region, const Points& points, radfmt::MeshData& mesh,
          std::initializer_list<std::uint32_t> corners) {
    radfmt::Patch p;
    std::copy(corners.begin(), corners.end(), p.corners.begin());
    std::vector<Vec3> pts;
    for (const auto c : corners) pts.push_back(points.position[c]);
    p.group = region.group;
    p.material = region.material;
    p.normal = region.plane.normal;
    p.area = 0.5 * length(newell_normal(pts));
    p.centroid = polygon_centroid(pts);
    mesh.patches.push_back(p);
}

// Points of one straight run of outline, off their line by rounding alone (a glTF's floats),
// make slivers outside the pieces: a triangle no higher than the tolerance that decides which
// points are on a line has no area worth a patch, and is not part of the region. From twice
// its area and its longest edge squared.
bool higher_than_tolerance(double twice_area, double longest_squared, double tolerance) {
    const double longest = std::sqrt(longest_squared);
    return twice_area > std::max(tolerance, 1e-9 * longest) * longest;
}

bool has_area(const Point2& a, const Point2& b, const Point2& c, double tolerance) {
    const double longest = std::max(
        {CGAL::squared_distance(a, b), CGAL::squared_distance(b, c), CGAL::squared_distance(c, a)});
    return higher_than_tolerance(std::abs(CGAL::area(a, b, c)) * 2, longest, tolerance);
}

double band_area(const BandCDT& cdt) {
    double area = 0;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        if (f->is_in_domain())
            area += std::abs(
                CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()));
    return area;
}

// The band: a constrained Delaunay triangulation of the region minus its whole cells, with the
// grid nodes well inside it as extra points, refined until no triangle has an angle under
// about 20 degrees or an edge over a cell, where that needs no point on the band's outline.
void triangulate_band(const Region& region, RegionGrid& grid, const std::vector<EdgeKey>& band,
                      Points& points, radfmt::MeshData& mesh, SurfaceReport& report,
                      double tolerance) {
    BandCDT cdt;
    auto insert = [&](std::uint32_t id, const XY& xy) {
        const auto v = cdt.insert(Point2(xy[0], xy[1]));
        if (v->info().id == kNone) v->info().id = id;
        return v;
    };
    std::unordered_map<std::uint32_t, XY> node_xy; // grid nodes keep their exact grid position
    for (std::size_t j = 0; j <= grid.nv(); ++j)
        for (std::size_t i = 0; i <= grid.nu(); ++i)
            if (grid.id(i, j) != kNone) node_xy[grid.id(i, j)] = grid.node_xy(i, j);
    auto xy_of = [&](std::uint32_t id) {
        const auto it = node_xy.find(id);
        return it != node_xy.end() ? it->second : region.plane.to_2d(points.position[id]);
    };
    for (const auto e : band) {
        const auto a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
        const auto va = insert(a, xy_of(a)), vb = insert(b, xy_of(b));
        if (va != vb) cdt.insert_constraint(va, vb);
    }
    for (std::size_t j = 0; j <= grid.nv(); ++j)
        for (std::size_t i = 0; i <= grid.nu(); ++i)
            if (grid.node_ok(i, j) && grid.id(i, j) == kNone) {
                const auto xy = grid.node_xy(i, j);
                if (grid.full_at(xy)) continue;
                grid.id(i, j) = points.add(region.plane.to_3d(xy[0], xy[1]));
                insert(grid.id(i, j), xy);
            }
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) {
        bool in = !cdt.is_infinite(f);
        if (in) {
            const auto &a = f->vertex(0)->point(), &b = f->vertex(1)->point(),
                       &d = f->vertex(2)->point();
            const auto c = CGAL::centroid(a, b, d);
            in =
                region.contains(c) && !grid.full_at({c.x(), c.y()}) && has_area(a, b, d, tolerance);
        }
        f->set_in_domain(in);
    }
    if (region.cell > 0) {
        CGAL::Delaunay_mesher_no_edge_refinement_2<BandCDT, BandCriteria> mesher(
            cdt, BandCriteria(region.cell, cdt));
        mesher.init(true);
        // The aspect bound is past what Delaunay refinement is proven to reach: a budget of
        // points, a few for every cell of the band and every constrained edge.
        const auto budget = static_cast<std::size_t>(
            16 * band_area(cdt) / (region.cell * region.cell) + 8 * band.size() + 64);
        for (std::size_t step = 0; step < budget && mesher.step_by_step_refine_mesh(); ++step) {
        }
    }
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
        if (v->info().id == kNone)
            v->info().id = points.add(region.plane.to_3d(v->point().x(), v->point().y()));
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (!f->is_in_domain() || !has_area(f->vertex(0)->point(), f->vertex(1)->point(),
                                            f->vertex(2)->point(), tolerance))
            continue;
        // The same in space (a point of a run that leaves the region's plane by its tolerance).
        const Vec3 &p0 = points.position[f->vertex(0)->info().id],
                   &p1 = points.position[f->vertex(1)->info().id],
                   &p2 = points.position[f->vertex(2)->info().id];
        const double longest =
            std::max({dot(p1 - p0, p1 - p0), dot(p2 - p1, p2 - p1), dot(p0 - p2, p0 - p2)});
        if (!higher_than_tolerance(length(cross(p1 - p0, p2 - p0)), longest, tolerance)) continue;
        emit(region, points, mesh,
             {f->vertex(0)->info().id, f->vertex(1)->info().id, f->vertex(2)->info().id});
        ++report.band_triangles;
    }
}

// A quadrilateral region's bilinear grid: its sides' points are the grid's outer nodes.
void grid_quadrilateral(const Region& region, Points& points, radfmt::MeshData& mesh,
                        SurfaceReport& report) {
    const auto& s = region.quad_sides;
    const std::size_t nu = s[0].size() - 1, nv = s[1].size() - 1;
    const Vec3 p00 = points.position[s[0].front()], p10 = points.position[s[1].front()],
               p11 = points.position[s[2].front()], p01 = points.position[s[3].front()];
    std::vector<std::uint32_t> id((nu + 1) * (nv + 1));
    auto at = [&](std::size_t i, std::size_t j) -> std::uint32_t& { return id[j * (nu + 1) + i]; };
    for (std::size_t j = 0; j <= nv; ++j)
        for (std::size_t i = 0; i <= nu; ++i) {
            if (j == 0)
                at(i, j) = s[0][i];
            else if (i == nu)
                at(i, j) = s[1][j];
            else if (j == nv)
                at(i, j) = s[2][nu - i];
            else if (i == 0)
                at(i, j) = s[3][nv - j];
            else {
                const double a = double(i) / double(nu), b = double(j) / double(nv);
                at(i, j) = points.add(p00 * ((1 - a) * (1 - b)) + p10 * (a * (1 - b)) +
                                      p11 * (a * b) + p01 * ((1 - a) * b));
            }
        }
    for (std::size_t j = 0; j < nv; ++j)
        for (std::size_t i = 0; i < nu; ++i) {
            emit(region, points, mesh, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            ++report.cells;
        }
}

// grid_quadrilateral unless a cell's aspect is over 3 (a quadrilateral far from a
// parallelogram): then nothing is added, and the region is gridded as any other.
bool grid_shapely_quadrilateral(const Region& region, Points& points, radfmt::MeshData& mesh,
                                SurfaceReport& report) {
    const auto kept = points.position.size();
    radfmt::MeshData trial;
    SurfaceReport counts;
    grid_quadrilateral(region, points, trial, counts);
    if (!std::all_of(trial.patches.begin(), trial.patches.end(), [&](const auto& patch) {
            return patch_aspect(points.position, patch) <= 3;
        })) {
        points.position.resize(kept);
        return false;
    }
    mesh.patches.insert(mesh.patches.end(), trial.patches.begin(), trial.patches.end());
    report.cells += counts.cells;
    return true;
}

// The region's whole cells as quads, and the band between them and the outline.
void mesh_cells_and_band(const Region& region, RegionGrid& grid,
                         const std::unordered_set<EdgeKey>& pieces, Points& points,
                         radfmt::MeshData& mesh, SurfaceReport& report, double tolerance) {
    std::unordered_set<EdgeKey> band(pieces.begin(), pieces.end());
    auto toggle = [&](EdgeKey e) {
        if (!band.erase(e)) band.insert(e);
    };
    for (std::size_t j = 0; j < grid.nv(); ++j)
        for (std::size_t i = 0; i < grid.nu(); ++i) {
            if (!grid.full(i, j)) continue;
            const std::array<std::array<std::size_t, 2>, 4> c{
                {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
            for (const auto& [a, b] : c)
                if (grid.id(a, b) == kNone) {
                    const auto p = grid.node_xy(a, b);
                    grid.id(a, b) = points.add(region.plane.to_3d(p[0], p[1]));
                }
            emit(region, points, mesh,
                 {grid.id(i, j), grid.id(i + 1, j), grid.id(i + 1, j + 1), grid.id(i, j + 1)});
            ++report.cells;
            for (int k = 0; k < 4; ++k)
                toggle(edge_key(grid.id(c[k][0], c[k][1]),
                                grid.id(c[(k + 1) % 4][0], c[(k + 1) % 4][1])));
        }
    if (band.empty()) return;
    std::vector<EdgeKey> ordered(band.begin(), band.end());
    std::sort(ordered.begin(), ordered.end()); // the same triangulation whatever the hash order
    triangulate_band(region, grid, ordered, points, mesh, report, tolerance);
}

// Rounds of giving cells to the band: enough for a cell's neighbours to follow it.
constexpr int kMaxBandRounds = 2;

// The whole cells with a corner on a band triangle of aspect over 3 (sorted, once each).
std::vector<std::array<std::size_t, 2>> cells_at_bad_triangles(const RegionGrid& grid,
                                                               const radfmt::MeshData& trial,
                                                               const Points& points) {
    std::unordered_map<std::uint32_t, std::array<std::size_t, 2>> node_of;
    for (std::size_t j = 0; j <= grid.nv(); ++j)
        for (std::size_t i = 0; i <= grid.nu(); ++i)
            if (grid.id(i, j) != kNone) node_of[grid.id(i, j)] = {i, j};
    std::vector<std::array<std::size_t, 2>> cells;
    for (const auto& patch : trial.patches) {
        if (patch.corner_count() != 3 || patch_aspect(points.position, patch) <= 3) continue;
        for (int k = 0; k < 3; ++k) {
            const auto it = node_of.find(patch.corners[k]);
            if (it == node_of.end()) continue;
            const auto [i, j] = it->second;
            for (const auto di : {0, 1})
                for (const auto dj : {0, 1})
                    if (i >= std::size_t(di) && j >= std::size_t(dj) && i - di < grid.nu() &&
                        j - dj < grid.nv() && grid.full(i - di, j - dj))
                        cells.push_back({i - di, j - dj});
        }
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return cells;
}

} // namespace

void grid_region(const Region& region, Points& points, radfmt::MeshData& mesh,
                 SurfaceReport& report, double tolerance) {
    if (!region.quad_sides.empty() && grid_shapely_quadrilateral(region, points, mesh, report))
        return;
    std::vector<std::uint32_t> ids;
    for (const auto& [a, b] : region.pieces) ids.push_back(a), ids.push_back(b);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<XY> xy;
    std::vector<Point2> pts;
    for (const auto id : ids) {
        xy.push_back(region.plane.to_2d(points.position[id]));
        pts.emplace_back(xy.back()[0], xy.back()[1]);
    }
    GridFrame frame;
    if (!minimum_rectangle(pts, frame)) return; // no area
    RegionGrid grid(region, frame, xy, ids, points, tolerance);
    std::unordered_set<EdgeKey> pieces;
    for (const auto& [a, b] : region.pieces) pieces.insert(edge_key(a, b));
    grid.classify_nodes(pieces);
    // The band's refinement may not split a cell's sides: a bad triangle at a cell's corner
    // stays bad. Such cells are given to the band and the region meshed again.
    for (int round = 0;; ++round) {
        const auto kept = points.position.size();
        RegionGrid trial_grid = grid;
        radfmt::MeshData trial;
        SurfaceReport counts;
        mesh_cells_and_band(region, trial_grid, pieces, points, trial, counts, tolerance);
        std::vector<std::array<std::size_t, 2>> cells;
        if (round < kMaxBandRounds) cells = cells_at_bad_triangles(trial_grid, trial, points);
        if (cells.empty()) {
            counts.joined = join_triangles(region, points, trial, 0);
            counts.band_triangles -= 2 * counts.joined;
            mesh.patches.insert(mesh.patches.end(), trial.patches.begin(), trial.patches.end());
            report.cells += counts.cells;
            report.band_triangles += counts.band_triangles;
            report.joined += counts.joined;
            break;
        }
        points.position.resize(kept);
        for (const auto& [i, j] : cells) grid.give_to_band(i, j);
    }
}

} // namespace rad::surfaces
