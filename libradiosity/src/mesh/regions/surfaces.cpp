// mesh_surfaces: the passes of planar regions in order, and the shape statistics.
#include "radiosity/surfaces.hpp"

#include "mesh/geometry/polygon2d.hpp"
#include "mesh/geometry/square_index.hpp"
#include "mesh/load/weld.hpp"
#include "mesh/regions/regions.hpp"
#include "radiosity/error.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/stages.hpp"
#include "radiosity/two_sided.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rad {

namespace {

// A region's cell side from --max-edge and --max-area (the smaller wins).
double cell_side(const radfmt::MeshData& faces, std::uint32_t group, const SurfaceOptions& o) {
    const auto& name = group < faces.groups.size() ? faces.groups[group] : std::string();
    const double edge = limit_for(o.max_edge_by_group, name, o.max_edge);
    const double area = limit_for(o.max_area_by_group, name, o.max_area);
    double side = edge;
    if (area > 0) side = side > 0 ? std::min(side, std::sqrt(area)) : std::sqrt(area);
    return side;
}

// A region thinner than its cell is cut across into pieces twice its width long (near-square
// patches). One thinner than a tenth of a cell (a trim, a sill) keeps pieces of a cell: its
// patches are as thin as it is, and cutting it into specks would spend patches on detail the
// rest of the scene is not resolved to.
double piece_length(double cell, double width) {
    return width_class(cell, width) == WidthClass::Narrow ? 2 * width : cell;
}

} // namespace

WidthClass width_class(double cell, double width) {
    if (!(cell > 0) || width >= cell) return WidthClass::Wide;
    return width >= cell / 10 ? WidthClass::Narrow : WidthClass::Thin;
}

namespace {

// The polygons' corners listed again in the patches' order, without those of polygons that
// joined another speck since.
void compact_polygon_corners(radfmt::MeshData& mesh) {
    if (mesh.polygon_corners.empty()) return;
    radfmt::MeshData compact;
    for (auto& p : mesh.patches) {
        if (!p.is_polygon()) continue;
        const auto corners = mesh.corners(p);
        const std::vector<std::uint32_t> list(corners.begin(), corners.end());
        compact.set_corners(p, list, true);
    }
    mesh.polygon_corners = std::move(compact.polygon_corners);
}

// Vertices renumbered to those the patches use, in order of first use.
void drop_unused_vertices(radfmt::MeshData& mesh) {
    std::vector<std::uint32_t> new_id(mesh.vertices.size(), surfaces::kNone);
    std::vector<Vec3> kept;
    for (auto& p : mesh.patches)
        for (auto& c : mesh.corners(p)) {
            if (new_id[c] == surfaces::kNone) {
                new_id[c] = static_cast<std::uint32_t>(kept.size());
                kept.push_back(mesh.vertices[c]);
            }
            c = new_id[c];
        }
    mesh.vertices = std::move(kept);
}

// The shorter side of the region's minimum-area rectangle, or its thickness (the diameter of the
// largest circle inside it) where that is under half the side: a frame of thin strips, a ring
// or an L of thin arms is thin, though its rectangle is not. (Any compact shape's circle is
// over half its rectangle's side: a triangle's at least two thirds.)
double width_or_thickness(const surfaces::Region& region, const surfaces::Points& points) {
    const double side = surfaces::region_width(region, points);
    if (!(region.cell > 0)) return side;
    // Past a cell, or past half the side, the region is what its rectangle says: stop there.
    const double enough = std::min(side / 2, region.cell);
    const double thickness = surfaces::region_thickness(region, points, enough, region.cell / 100);
    return thickness < enough ? thickness : side;
}

// Whether a patch of a wide region may lie where the region is thinner: a band triangle of
// aspect over 3, or one under a tenth of a cell (a wide region's cells are neither).
bool suspect_in_wide_region(const radfmt::Patch& patch, const surfaces::Points& points, double cell,
                            std::span<const std::uint32_t> polygon_corners) {
    return patch_aspect(points.position, patch, polygon_corners) > 3 ||
           is_speck(points.position, patch, cell, polygon_corners);
}

// A region's outline pieces shorter than `small`, in squares of that side in its plane: those
// within `small` of a point are in the 3 x 3 squares around it.
class ShortPieces {
  public:
    ShortPieces(const surfaces::Region& region, const surfaces::Points& points, double small)
        : region_(region), small_(small), index_(small) {
        for (const auto& [a, b] : region.pieces) {
            const auto pa = xy(points.position[a]), pb = xy(points.position[b]);
            if (!(std::hypot(pb[0] - pa[0], pb[1] - pa[1]) < small)) continue;
            index_.insert({std::min(pa[0], pb[0]), std::min(pa[1], pb[1])},
                          {std::max(pa[0], pb[0]), std::max(pa[1], pb[1])},
                          static_cast<std::uint32_t>(pieces_.size()));
            pieces_.push_back({pa, pb});
        }
        index_.freeze();
    }
    bool empty() const { return pieces_.empty(); }
    // Whether a piece lies within `small` of p.
    bool near(const Vec3& p) const {
        const auto q = xy(p);
        return index_.find_near(q, 1, [&](std::uint32_t piece) {
            return segment_distance(q, pieces_[piece][0], pieces_[piece][1]) < small_;
        });
    }

  private:
    Point2d xy(const Vec3& p) const {
        const auto v = region_.plane.to_2d(p);
        return {v[0], v[1]};
    }
    const surfaces::Region& region_;
    double small_;
    std::vector<std::array<Point2d, 2>> pieces_;
    SquareIndex index_;
};

// Marks the region's patches under a tenth of a cell (mesh's from `first` on) that lie within
// a tenth of a cell of an outline piece that short: well-shaped triangles beside a notch or a
// step of the input's outline must be about its size.
void mark_specks_at_detail(const surfaces::Region& region, const surfaces::Points& points,
                           const radfmt::MeshData& mesh, std::size_t first,
                           std::vector<bool>& at_detail) {
    at_detail.resize(mesh.patches.size(), false);
    if (!(region.cell > 0)) return;
    const ShortPieces short_pieces(region, points, region.cell / 10);
    if (short_pieces.empty()) return;
    for (std::size_t k = first; k < mesh.patches.size(); ++k) {
        const auto& patch = mesh.patches[k];
        if (!is_speck(points.position, patch, region.cell, mesh.polygon_corners)) continue;
        for (const auto c : mesh.corners(patch))
            at_detail[k] = at_detail[k] || short_pieces.near(points.position[c]);
    }
}

// Marks the patches of a wide region (mesh's from `first` on) that lie where it is under a
// cell wide as narrow: the largest circle inside the region around the patch, among those
// local_thickness tries, is under a cell (a strip between two outlines).
void mark_narrow_parts(const surfaces::Region& region, const surfaces::Points& points,
                       const radfmt::MeshData& mesh, std::size_t first,
                       std::vector<WidthClass>& classes) {
    std::vector<bool> wanted(mesh.patches.size() - first);
    bool any = false;
    for (std::size_t k = first; k < mesh.patches.size(); ++k)
        any |= wanted[k - first] =
            suspect_in_wide_region(mesh.patches[k], points, region.cell, mesh.polygon_corners);
    if (!any) return;
    const auto local = surfaces::local_thickness(region, points, mesh, first, wanted, region.cell);
    for (std::size_t k = 0; k < local.size(); ++k)
        if (local[k] < region.cell) classes[first + k] = WidthClass::Narrow;
}

// The width class of each of the region's patches (mesh's from `first` on): the region's, or
// thinner where the region is thinner there. Thin where no circle a tenth of a cell across
// inside the region holds the patch's centroid, decided exactly (a tab or a strip of a wider
// region, a notch's neck, the tip of an acute corner); else narrow where a wide region is under
// a cell wide.
void classify_patches(const surfaces::Region& region, const surfaces::Points& points,
                      const radfmt::MeshData& mesh, std::size_t first,
                      std::vector<WidthClass>& classes, std::vector<double>& cells) {
    const auto whole = width_class(region.cell, region.width);
    classes.resize(mesh.patches.size(), whole);
    cells.resize(mesh.patches.size(), region.cell);
    if (whole == WidthClass::Thin) return;
    if (whole == WidthClass::Wide) mark_narrow_parts(region, points, mesh, first, classes);
    const auto held = surfaces::held_by_circle(region, points, mesh, first, region.cell / 10);
    for (std::size_t k = 0; k < held.size(); ++k)
        if (!held[k]) classes[first + k] = WidthClass::Thin;
}

// What pass 4 knows of each patch, for the summary.
struct PatchClasses {
    std::vector<WidthClass> width;
    std::vector<double> cell;
    std::vector<bool> at_detail;
    // Patches [from, to) again, for their copies.
    void repeat(std::size_t from, std::size_t to) {
        for (auto i = from; i < to; ++i) {
            width.push_back(width[i]);
            cell.push_back(cell[i]);
            at_detail.push_back(at_detail[i]);
        }
    }
};

// The patches [from, to) of a region's twin, reversed, as `region`'s.
void add_backs(const surfaces::Region& region, std::size_t from, std::size_t to,
               radfmt::MeshData& mesh) {
    for (auto i = from; i < to; ++i) {
        auto back = back_of(mesh, mesh.patches[i]);
        back.group = region.group;
        back.material = region.material;
        mesh.patches.push_back(back);
    }
}

// Pass 4 over every region: its patches (over `points`), classified, its specks joined, and
// the shapes' summary in the report. A region with a twin (twin_regions) gets the twin's
// patches reversed.
radfmt::MeshData grid_regions(const std::vector<surfaces::Region>& regions,
                              const std::vector<std::uint32_t>& twin, surfaces::Points& points,
                              const SurfaceOptions& options, double tolerance, SurfaceReport& rep) {
    radfmt::MeshData mesh;
    PatchClasses known;
    auto& classes = known.width;
    auto& cell_of_patch = known.cell;
    auto& at_detail = known.at_detail;
    std::vector<std::pair<std::size_t, std::size_t>> patches_of(regions.size());
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const auto& region = regions[r];
        if (r % 1024 == 0) stage_fraction(options.stages, double(r) / regions.size());
        const auto first = mesh.patches.size();
        if (twin[r] != surfaces::kNone) {
            const auto [from, to] = patches_of[twin[r]];
            add_backs(region, from, to, mesh);
            known.repeat(from, to);
            patches_of[r] = {first, mesh.patches.size()};
            continue;
        }
        surfaces::grid_region(region, points, mesh, rep, tolerance);
        // Where a region is thinner than a tenth of a cell its patches are slivers by its own
        // shape; where under a cell, it is cut across into near-square patches.
        classify_patches(region, points, mesh, first, classes, cell_of_patch);
        if (const auto joined = surfaces::merge_specks(region, points, mesh, first, classes)) {
            rep.specks_joined += joined;
            classes.resize(first);
            cell_of_patch.resize(first);
            classify_patches(region, points, mesh, first, classes, cell_of_patch);
        }
        mark_specks_at_detail(region, points, mesh, first, at_detail);
        patches_of[r] = {first, mesh.patches.size()};
    }
    compact_polygon_corners(mesh);
    mesh.vertices = points.position;
    rep.shape = shape_stats(mesh, classes, cell_of_patch, at_detail);
    return mesh;
}

} // namespace

radfmt::MeshData mesh_surfaces(const radfmt::MeshData& input, const SurfaceOptions& options,
                               SurfaceReport* report) {
    SurfaceReport local;
    SurfaceReport& rep = report ? *report : local;
    rep.faces = input.patches.size();
    // Pass 0 keeps the input's vertices: one weld serves both it and the regions.
    const auto weld = weld_by_position(input.vertices);
    surfaces::Points points;
    const std::uint32_t count = weld.empty() ? 0 : *std::max_element(weld.begin(), weld.end()) + 1;
    points.position.assign(count, Vec3{});
    std::vector<bool> placed(count, false);
    for (std::size_t v = 0; v < input.vertices.size(); ++v)
        if (!placed[weld[v]]) placed[weld[v]] = true, points.position[weld[v]] = input.vertices[v];
    const double size = bounds(input.vertices).diagonal();
    std::vector<double> cell_of_group(std::max<std::size_t>(input.groups.size(), 1));
    for (std::uint32_t g = 0; g < cell_of_group.size(); ++g)
        cell_of_group[g] = cell_side(input, g, options);
    const auto merged = surfaces::merge_curved_strips(input, weld, points, cell_of_group, options,
                                                      size, rep.strips);
    const auto& faces = merged ? *merged : input;
    const double tolerance = 1e-7 * size;

    begin_stage(options.stages, "planar regions");
    auto regions = surfaces::find_planar_regions(faces, weld, points, options, size, tolerance);
    double cells = 0;
    for (auto& region : regions) {
        region.cell = cell_side(faces, region.group, options);
        double area = 0;
        for (const auto f : region.faces) area += faces.patches[f].area;
        // Whole cells, and about one triangle per face along the outline.
        if (region.cell > 0) cells += area / (region.cell * region.cell);
        cells += double(region.faces.size());
    }
    if (!(cells <= options.max_patches)) {
        char text[160];
        std::snprintf(text, sizeof text, "about %.3g patches, more than --max-patches %.3g", cells,
                      options.max_patches);
        throw InputError(options.source + ": these limits (--max-edge, --max-area) would make " +
                         text + " (use larger limits, or raise --max-patches)");
    }
    begin_stage(options.stages, "outlines");
    for (auto& region : regions) {
        surfaces::trace_outline(region, faces, weld, points, options.source);
        if (region.area_beyond_union > 0)
            ++rep.overlapped_regions, rep.overlap_area += region.area_beyond_union;
        region.width = width_or_thickness(region, points);
        region.piece = piece_length(region.cell, region.width);
    }
    begin_stage(options.stages, "outline runs");
    rep.regions = regions.size();
    rep.dropped_vertices = surfaces::split_outline_runs(regions, points, tolerance);
    surfaces::OutlineGrowth growth;
    surfaces::fill_small_holes(regions, points, growth);
    rep.t_vertices = surfaces::relax_outline_points(regions, points, tolerance, growth);
    rep.holes_filled = growth.holes;
    rep.bends_cut = growth.points;
    rep.area_covered = growth.area;
    begin_stage(options.stages, "outline refinement");
    surfaces::refine_outline_pieces(regions, points, tolerance, 6);
    begin_stage(options.stages, "grids");
    auto mesh = grid_regions(regions, surfaces::twin_regions(regions, faces, weld), points, options,
                             tolerance, rep);
    mesh.groups = faces.groups;
    mesh.materials = faces.materials;
    drop_unused_vertices(mesh);
    if (mesh.patches.size() >= radfmt::kNoVertex)
        throw InputError("too many patches for 32-bit indices");
    return mesh;
}

double longest_edge(const radfmt::MeshData& mesh, const radfmt::Patch& patch) {
    return longest_edge(mesh.vertices, patch, mesh.polygon_corners);
}

double longest_edge(std::span<const Vec3> vertices, const radfmt::Patch& patch,
                    std::span<const std::uint32_t> polygon_corners) {
    const auto corners = radfmt::patch_corners(patch, polygon_corners);
    const std::size_t n = corners.size();
    double longest = 0;
    for (std::size_t k = 0; k < n; ++k)
        longest = std::max(longest, length(vertices[corners[(k + 1) % n]] - vertices[corners[k]]));
    return longest;
}

bool is_speck(std::span<const Vec3> vertices, const radfmt::Patch& patch, double cell,
              std::span<const std::uint32_t> polygon_corners) {
    return longest_edge(vertices, patch, polygon_corners) < cell / 10;
}

double patch_aspect(const radfmt::MeshData& mesh, const radfmt::Patch& patch) {
    return patch_aspect(mesh.vertices, patch, mesh.polygon_corners);
}

double patch_aspect(std::span<const Vec3> vertices, const radfmt::Patch& patch,
                    std::span<const std::uint32_t> polygon_corners) {
    if (!(patch.area > 0)) return 1e300;
    if (patch.is_polygon()) {
        const auto corners = radfmt::patch_corners(patch, polygon_corners);
        double diameter = 0;
        for (std::size_t a = 0; a < corners.size(); ++a)
            for (std::size_t b = a + 1; b < corners.size(); ++b)
                diameter = std::max(diameter, length(vertices[corners[a]] - vertices[corners[b]]));
        return diameter * diameter / (2 * patch.area);
    }
    const int n = patch.corner_count();
    std::array<Vec3, 4> c;
    for (int k = 0; k < n; ++k) c[k] = vertices[patch.corners[k]];
    double longest = 0;
    std::array<double, 4> side{};
    for (int k = 0; k < n; ++k) {
        side[k] = length(c[(k + 1) % n] - c[k]);
        longest = std::max(longest, side[k]);
    }
    if (n == 3) return longest * longest / (2 * patch.area);
    // A quad's heights: its area over the mean length of each pair of opposite sides.
    const double h1 = patch.area / std::max(1e-300, 0.5 * (side[0] + side[2]));
    const double h2 = patch.area / std::max(1e-300, 0.5 * (side[1] + side[3]));
    return longest / std::min(h1, h2);
}

ShapeStats shape_stats(const radfmt::MeshData& mesh, const std::vector<WidthClass>& classes,
                       const std::vector<double>& cells, const std::vector<bool>& at_detail) {
    ShapeStats stats;
    std::size_t good[2] = {0, 0}, counted[2] = {0, 0};
    stats.worst_aspect = 0;
    for (std::size_t k = 0; k < mesh.patches.size(); ++k) {
        const auto c = k < classes.size() ? classes[k] : WidthClass::Wide;
        if (c == WidthClass::Thin) {
            ++stats.thin;
            continue;
        }
        const auto& patch = mesh.patches[k];
        const double a = patch_aspect(mesh, patch);
        const bool fine = a <= 3;
        ++counted[0], good[0] += fine; // a tenth of a cell thick or more
        if (c == WidthClass::Wide) ++counted[1], good[1] += fine;
        stats.worst_aspect = std::max(stats.worst_aspect, a);
        if (k < cells.size() && is_speck(mesh.vertices, patch, cells[k], mesh.polygon_corners))
            ++(k < at_detail.size() && at_detail[k] ? stats.specks_at_detail : stats.specks);
    }
    stats.fraction_aspect_at_most_3 = counted[0] ? double(good[0]) / double(counted[0]) : 1;
    stats.fraction_wide_aspect_at_most_3 = counted[1] ? double(good[1]) / double(counted[1]) : 1;
    return stats;
}

} // namespace rad
