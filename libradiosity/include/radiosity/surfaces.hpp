// Patches from surfaces, not from the input's triangles (rad-mesh's default): connected faces
// that lie in one plane and share material and group are merged into one planar region (a
// polygon with holes), and each region is gridded into near-square patches aligned with its
// own minimum-area bounding rectangle. A wall drawn as one quad, as two triangles or as a fan
// of slivers meshes to the same grid.
#pragma once
#include "radfmt/kinds.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace rad {

class StageLog;

constexpr double kDefaultMaxSag = 0.02; // rad-mesh --max-sag

struct SurfaceOptions {
    double max_edge = 0; // a full cell's side; 0: each region as few patches as its shape allows
    double max_area = 0; // a full cell's area at most (0: no limit)
    std::map<std::string, double> max_edge_by_group;
    std::map<std::string, double> max_area_by_group;
    // Faces belong to one region when their normals agree within this angle (degrees) and
    // their corners lie within `plane_tolerance` x the scene's size of the region's plane.
    double angle_tolerance = 0.5;
    double plane_tolerance = 1e-5;
    // Lines planar regions are not joined across (Scene::contact_lines): where a wall meets a
    // ceiling, the ceiling's patches on each side see their own room.
    std::vector<std::array<radfmt::Vec3, 2>> creases;
    double max_patches = 2e7; // refused before gridding when the cells would be more
    // A curved surface drawn as long thin facets (under a tenth of a cell wide) is taken as
    // planar faces across runs of them, each no farther from the facets' edges than this
    // fraction of a cell (nor than a chord of an arc turning 30 degrees), and no wider than a
    // cell (0: the facets as drawn). Refined, the faces converge to the facets.
    double max_sag = kDefaultMaxSag;
    std::string source;         // the scene file, for messages
    StageLog* stages = nullptr; // shows how far the stage is (optional)
};

// Shape of a patch mesh, for rad-mesh's summary and the tests: a patch's aspect is its longest
// edge over its shortest height (longest^2 / (2 area) for a triangle: 1.15 equilateral; for a
// quad, the longest edge over its area / the mean length of each pair of opposite sides: 1 for
// a square).
// A region's width (the shorter side of its minimum-area rectangle, or its thickness, the
// diameter of the largest circle inside it, where under half that: frames, rings) against its
// cell: wide (a cell or more: near-square patches of a cell), narrow (a tenth of a cell or more:
// cut across into near-square patches twice its width long) or thin (a trim or sill: patches as
// thin as the region, a cell long). A patch of a wider region is thin where the region is that
// thin there: no circle a tenth of a cell across inside the region holds its centroid (a tab or
// a neck of a narrow region, a sliver between two outlines, the tip of an acute corner).
enum class WidthClass : std::uint8_t { Wide, Narrow, Thin }; // in order of thinness
WidthClass width_class(double cell, double width);           // no cell (0): wide
struct ShapeStats {
    double fraction_aspect_at_most_3 = 1;      // of the patches not thin
    double fraction_wide_aspect_at_most_3 = 1; // of the patches of wide regions
    double worst_aspect = 1;                   // of the patches not thin
    std::size_t thin = 0;                      // patches where the region is thin, not counted
    // Patches not thin whose longest edge is under a tenth of a cell: beside an outline piece
    // that short (within a tenth of a cell of it: the input's notches and steps), and elsewhere.
    std::size_t specks_at_detail = 0;
    std::size_t specks = 0;
};
double patch_aspect(const radfmt::MeshData& mesh, const radfmt::Patch& patch);
// The same with the corners read from `vertices` (a mesh's, or points a mesh is being made of)
// and a polygon's from `polygon_corners` (a mesh's). A polygon's aspect is its diameter^2 /
// (2 x area): a triangle's measure (longest side over shortest height) for a triangle, 1 for
// a square.
double patch_aspect(std::span<const radfmt::Vec3> vertices, const radfmt::Patch& patch,
                    std::span<const std::uint32_t> polygon_corners = {});
double longest_edge(const radfmt::MeshData& mesh, const radfmt::Patch& patch);
double longest_edge(std::span<const radfmt::Vec3> vertices, const radfmt::Patch& patch,
                    std::span<const std::uint32_t> polygon_corners = {});
// A speck: every edge under a tenth of `cell` (the patch's cell side).
bool is_speck(std::span<const radfmt::Vec3> vertices, const radfmt::Patch& patch, double cell,
              std::span<const std::uint32_t> polygon_corners = {});
// Over the patches not thin (`classes` by patch; patches past its end are wide); `cells` gives
// each patch's cell side (patches past its end are not counted as specks); `at_detail` marks
// the specks beside an outline piece under a tenth of a cell.
ShapeStats shape_stats(const radfmt::MeshData& mesh, const std::vector<WidthClass>& classes = {},
                       const std::vector<double>& cells = {},
                       const std::vector<bool>& at_detail = {});

// What pass 0 (merge_curved_strips) did: thin facets of curved surfaces taken as planar faces
// across them.
struct StripMerge {
    std::size_t facets = 0, faces = 0, chains = 0; // input faces, the faces made, the surfaces
    double area_before = 0, area_after = 0;        // of the facets, of the faces made
    double worst_offset = 0; // the farthest a facet's edge lies from the face made in its place
};

struct SurfaceReport {
    std::size_t faces = 0, regions = 0;
    std::size_t cells = 0;          // full grid cells: quads
    std::size_t band_triangles = 0; // triangles between the cells and a region's outline
    std::size_t joined = 0; // quads of two band triangles: a speck or a sliver and its neighbour
    std::size_t specks_joined = 0;    // specks joined with a neighbour into a quad or polygon
    std::size_t dropped_vertices = 0; // collinear outline points no other region needs
    std::size_t t_vertices = 0;       // points a region left out where smoothing stops anyway
    // Where something rises from a region (a pipe through a floor, a pillar's foot): holes under
    // a tenth of a cell across filled, and reflex corners of short steps cut off (within a
    // twentieth of a cell), and the ground the regions gained by both.
    std::size_t holes_filled = 0, bends_cut = 0;
    double area_covered = 0;
    // Regions whose faces overlap in part (copies are gone before): meshed as their union,
    // which is this much less than the faces' sum.
    std::size_t overlapped_regions = 0;
    double overlap_area = 0;
    StripMerge strips;
    ShapeStats shape;
};

// The faces (triangles and planar convex quads, as `subdivide` makes them with no limits) as
// the patches of gridded planar regions. Outline points are shared between the regions along
// an edge (each straight run of outline between two corners is split once, for every region on
// it, into pieces of at most the smallest cell size of those regions), except that a region
// leaves out a point of a straight stretch between pieces under a tenth of a cell where no
// other region there is smoothed with it (T-vertices where crease smoothing stops). Inside,
// a cell whose corners are at least a third of a cell from the outline (or on an outline
// point) is a quad; the band between those cells and the outline is a constrained Delaunay
// triangulation (CGAL) of their corners and the outline points, whose specks and slivers are
// joined with a neighbour into a convex quad where that makes one of aspect at most 3. A speck
// still left, where the region is not thin, joins a neighbour into a polygon patch (or a quad).
radfmt::MeshData mesh_surfaces(const radfmt::MeshData& faces, const SurfaceOptions& options,
                               SurfaceReport* report = nullptr);

} // namespace rad
