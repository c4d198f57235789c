// The passes of mesh_surfaces (internal header): planar regions, their outlines, the outline
// runs shared between regions, and the grid of each region.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/surfaces.hpp"
#include "radiosity/vec.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace rad::surfaces {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = K::Point_2;
constexpr std::uint32_t kNone = 0xFFFFFFFFu;
struct VertexInfo {
    std::uint32_t id = kNone; // the point, once known
};
struct FaceInfo {
    bool inside = false;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<
    K, CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>>;
using CDT =
    CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                               CGAL::Exact_predicates_tag>;

using EdgeKey = std::uint64_t; // two point ids, smaller first
inline EdgeKey edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
}

// Every point of the pass, by id: the faces' welded corners first, then points made on the way.
struct Points {
    std::vector<Vec3> position;
    std::uint32_t add(const Vec3& p) {
        position.push_back(p);
        return static_cast<std::uint32_t>(position.size() - 1);
    }
};

// A plane with its own 2D axes (u x v = normal).
struct Plane {
    Vec3 origin{}, normal{}, u{}, v{};
    std::array<double, 2> to_2d(const Vec3& p) const {
        const Vec3 d = p - origin;
        return {dot(d, u), dot(d, v)};
    }
    Vec3 to_3d(double x, double y) const { return origin + u * x + v * y; }
};

using XY = std::array<double, 2>;

// The region's own axes: the minimum-area rectangle around its outline (one side of it lies
// along a side of the convex hull: rotating calipers, each side tried).
struct GridFrame {
    XY origin{}, e1{}, e2{}; // e2 is e1 turned a quarter counter-clockwise
    double length1 = 0, length2 = 0;
    // A point of the plane in the frame's own coordinates (along e1, along e2).
    XY local(const XY& p) const {
        const double dx = p[0] - origin[0], dy = p[1] - origin[1];
        return {dx * e1[0] + dy * e1[1], dx * e2[0] + dy * e2[1]};
    }
};
// False when the points span no area.
bool minimum_rectangle(const std::vector<Point2>& outline_points, GridFrame& frame);

// The sides of a region (closed loops, holes included) in the plane, in horizontal strips:
// whether a point is inside by the sides its strip crosses (even-odd).
class SideIndex {
  public:
    explicit SideIndex(std::vector<std::array<XY, 2>> sides);
    bool contains(double x, double y) const;

  private:
    std::size_t strip(double y) const;
    std::vector<std::array<XY, 2>> sides_;
    std::vector<std::vector<std::uint32_t>> strips_;
    double lo_ = 1e300, hi_ = -1e300, step_ = 1;
};

struct Region {
    std::vector<std::uint32_t> faces; // patches of the input mesh
    std::uint32_t group = 0, material = 0;
    Plane plane;
    double cell = 0;  // the full cell's side (0: no limit)
    double piece = 0; // the longest outline piece (0: no limit): the cell, less where thinner
    double width = 0; // the shorter side of its minimum-area rectangle, or less: its thickness
    // The region's faces triangulated with their edges as constraints, faces marked inside:
    // tells whether a point of the plane is in the region.
    // A region whose faces tile it (no overlaps) has none: its sides tell instead.
    std::unique_ptr<CDT> cdt;
    std::unique_ptr<SideIndex> sides;
    // Ground outside its faces that the region covers (passes 3a, 3b): holes filled, corners
    // cut off, each with its box.
    struct Covered {
        XY lo{}, hi{};
        std::vector<XY> polygon;
    };
    std::vector<Covered> covered;
    // Boundary edges, before the runs; its pieces once it has covered ground (passes 3a, 3b).
    std::vector<std::array<std::uint32_t, 2>> outline;
    // How much the faces' areas add up to more than the area they cover (from the outline's
    // triangulation; 0 where they tile it, or the difference is rounding): faces drawn partly
    // over each other.
    double area_beyond_union = 0;
    std::vector<std::array<std::uint32_t, 2>> pieces; // boundary pieces, after the runs
    // A region whose outline is four straight runs around a convex quadrilateral, with equal
    // piece counts on opposite sides: its sides' points counter-clockwise (side k from corner
    // k to corner k+1), gridded bilinearly into quads.
    std::vector<std::vector<std::uint32_t>> quad_sides;
    bool contains(const Point2& p) const;
};

class PointBuckets;
// Each face's welded edges (`weld`) split where another point lies on them, within `tolerance`
// (a neighbour's corner partway along the edge: a T-junction), as sub-edges keyed by their ends, in
// CSR form: faces that share a sub-edge touch along it, whether or not their corners meet there.
struct FaceSubEdges {
    // faces + 1 entries: face f's sub-edges are keys[start[f] .. start[f + 1]).
    std::vector<std::size_t> start;
    std::vector<EdgeKey> keys;
};

FaceSubEdges split_face_edges(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                              const PointBuckets& buckets, double tolerance);

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

// The sub-edges lying along the creases (between points that lie on one), sorted.
std::vector<EdgeKey> crease_edges(const std::vector<std::array<Vec3, 2>>& creases,
                                  const PointBuckets& buckets, double tolerance);

// Pass 0 (SurfaceOptions::max_sag): a curved surface drawn as long thin planar facets (each a
// quad, or two triangles across its diagonal, at least three times as long as wide and under a
// tenth of its group's cell wide: its patches would be slivers), neighbours sharing a long side
// that no other face has, in one group and material and wound alike (not across a crease, nor
// a side another surface's corner lies on), is taken as planar quads across runs of the facets:
// each quad's corners are the run's outer long sides' ends, every long side between lies within
// `max_sag` of the cell of it (and within what a chord of an arc turning 30 degrees would), and
// the quad is no wider than the cell; runs as few as that allows, as even as they pass. A run's
// first face becomes its quad, the rest are dropped. A ring of facets (a column) is cut at its
// first facet. Nothing (no copy) when no facets were merged; the faces made use the input's
// vertices, so `weld` and `points` (the input's welded points) hold for them too.
std::optional<radfmt::MeshData>
merge_curved_strips(const radfmt::MeshData& faces, const std::vector<std::uint32_t>& weld,
                    const Points& points, const std::vector<double>& cell_of_group,
                    const SurfaceOptions& options, double scene_size, StripMerge& merged);

// Pass 1: faces connected across welded edges, or along an edge that a neighbour's corner
// splits (a T-junction, a point within `tolerance` of the edge), with the same group and
// material, whose normals agree and whose corners lie in the seed face's plane, are one region.
// Not across an edge along one of options.creases (a contact line), nor one that another
// surface leaves the plane from (a wall welded to the floor between two rooms).
std::vector<Region> find_planar_regions(const radfmt::MeshData& faces,
                                        const std::vector<std::uint32_t>& weld,
                                        const Points& points, const SurfaceOptions& options,
                                        double scene_size, double tolerance);

// For each region, the earlier region that is its other side (the same welded points and
// area, facing the opposite way: a window drawn both ways, twins the coincident pass kept),
// or kNone. Pass 4 gives it that region's patches reversed, so the two are one sheet's two
// sides (find_twins pairs them; a ray meets the side facing it), not two grids crossing.
std::vector<std::uint32_t> twin_regions(const std::vector<Region>& regions,
                                        const radfmt::MeshData& faces,
                                        const std::vector<std::uint32_t>& weld);

// Pass 2: the region's outline (edges between its inside and outside, holes included), from a
// constrained triangulation of its faces' edges; crossings of overlapping faces become points.
// Refuses a region whose faces' edges cross at many more points than they have corners
// (`source` names the file): a stack of copies.
void trace_outline(Region& region, const radfmt::MeshData& faces,
                   const std::vector<std::uint32_t>& weld, Points& points,
                   const std::string& source);

// The shorter side of the region's minimum-area rectangle (from its outline edges).
double region_width(const Region& region, const Points& points);

// The diameter of the largest circle inside the region, within `precision`; the search stops
// once it finds one at least `enough` across (then the value is at least that).
double region_thickness(const Region& region, const Points& points, double enough,
                        double precision);

// Pass 3: outline edges split where another region's outline point lies on them, collinear
// points that no region needs dropped, and each straight run split into equal pieces no longer
// than the smallest cell of the regions along it. Returns the points dropped.
std::size_t split_outline_runs(std::vector<Region>& regions, Points& points, double tolerance);

// Which regions meet each region along its outline (its pieces as they stand when made), and
// whether what meets it there rises from its plane: every other region there has a normal
// further from the region's, either way, than rad-shade's crease angle (a wall on a floor, a
// pipe through it), and there is one. Ground a region covers past such a piece lies behind or
// inside what rises there.
class RisingWalls {
  public:
    explicit RisingWalls(const std::vector<Region>& regions);
    // The regions whose pieces end at p (sorted, once each).
    const std::vector<std::uint32_t>& regions_at(std::uint32_t p) const { return at_point_.at(p); }
    bool around_point(std::uint32_t self, std::uint32_t p) const;
    bool along_piece(std::uint32_t self, std::uint32_t a, std::uint32_t b) const;

  private:
    bool all_rise(std::uint32_t self, const std::vector<std::uint32_t>& others) const;
    const std::vector<Region>& regions_;
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> at_point_;
    std::unordered_map<EdgeKey, std::vector<std::uint32_t>> at_piece_;
};

// The region covers `polygon` (outside its faces, inside its pieces now): points in it are
// inside the region. (Its outline, once all is covered, is its pieces.)
void cover(Region& region, std::vector<XY> polygon);

// What passes 3a and 3b changed besides straight stretches, for the summary.
struct OutlineGrowth {
    std::size_t holes = 0;  // holes filled
    std::size_t points = 0; // bends cut off
    double area = 0;        // the area the regions gained
};

// Pass 3a: a hole of a region under a tenth of its cell across (its box's diagonal), where
// something rises along all of its pieces and at all of its points (RisingWalls), is filled:
// patches around a hole that small would be its size (specks), for light its area cannot
// change.
void fill_small_holes(std::vector<Region>& regions, const Points& points, OutlineGrowth& growth);

// Pass 3b: in each region not gridded as a quadrilateral, a piece shorter than a tenth of a cell
// is merged with its neighbour across a point the region may leave out: along a straight
// stretch, where every other region is never smoothed together with it (another material or
// group, or a bend past rad-shade's default crease angle); at a bend that turns the outline
// into the region (a reflex corner) no more than a twentieth of a cell from the merged piece,
// where something rises at the point and along both pieces (RisingWalls) and no other point of
// the region lies in the corner cut off. The merged pieces stay within the region's piece length.
// Returns the points left out on straight stretches (T-vertices); bends cut off are counted in
// `growth`.
std::size_t relax_outline_points(std::vector<Region>& regions, const Points& points,
                                 double tolerance, OutlineGrowth& growth);

// Pass 3c: each region gridded on trial (pass 4); the outline piece that a bad band triangle
// lies on, or whose diametral circle holds its circumcentre, is halved for every region that
// has it (never below a tenth of a cell), and those regions tried again, up to `rounds`
// times. Returns the points added.
std::size_t refine_outline_pieces(std::vector<Region>& regions, Points& points, double tolerance,
                                  int rounds);

// For each of mesh's patches from `first` on (the region's) marked in `wanted` (all when
// empty), the diameter of the largest circle inside the region that holds its centroid, among
// circles centred on nearby patches' centroids and edge midpoints (within two cells): how thin
// the region is where the patch lies; once a circle at least `enough` wide is found, that one.
// Patches not wanted, and all of a region with no cell, get 1e300.
std::vector<double> local_thickness(const Region& region, const Points& points,
                                    const radfmt::MeshData& mesh, std::size_t first,
                                    const std::vector<bool>& wanted = {}, double enough = 1e300);

// For each of mesh's patches from `first` on (the region's), whether a circle `diameter` across
// inside the region holds its centroid: exactly (to 1/20,000 of the diameter), where
// local_thickness only tries circles centred at nearby patches. No: the region is thinner than
// that where the patch lies.
std::vector<bool> held_by_circle(const Region& region, const Points& points,
                                 const radfmt::MeshData& mesh, std::size_t first, double diameter);

// Pass 4: the region's grid cells as quads and the band between them and its outline as
// triangles, appended to `mesh` (whose vertices are `points`, patches facing the region's way).
// A cell with a corner on a band triangle of aspect over 3 is given to the band (the band's
// refinement may not split the cells' sides), for up to two rounds; then join_triangles. A
// quadrilateral region is gridded bilinearly unless a cell would have an aspect over 3.
void grid_region(const Region& region, Points& points, radfmt::MeshData& mesh,
                 SurfaceReport& report, double tolerance);

// Pass 4's last step, on the region's patches (mesh's from `first` on; none with no cell): a
// triangle that is a speck (every edge under a tenth of a cell: beside the outline's short
// pieces) or a sliver (aspect over 3) is joined with a neighbouring triangle not a speck into
// one strictly convex quad, where that quad's aspect is at most 3 (the lowest such). Returns the
// quads made.
std::size_t join_triangles(const Region& region, const Points& points, radfmt::MeshData& mesh,
                           std::size_t first);

// After the patches' classes are known (`classes`, by patch): each speck of the region
// (mesh's patches from `first` on) that is not where the region is thin joins the neighbour
// across one of its sides into one patch whose outline is star-shaped from a corner (of at
// most 12 corners; a quad when that is four strictly convex, else a polygon patch), choosing
// a join that is no speck, then the lowest diameter^2 / (2 x area). A join still a speck may
// join again. Returns the specks joined.
std::size_t merge_specks(const Region& region, const Points& points, radfmt::MeshData& mesh,
                         std::size_t first, const std::vector<WidthClass>& classes);

} // namespace rad::surfaces
