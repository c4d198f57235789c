// mesh_surfaces: the passes of planar regions in order, and the shape statistics.
#include "radiosity/surfaces.hpp"

#include "radiosity/error.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/stages.hpp"
#include "regions.hpp"
#include "weld.hpp"

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

// Vertices renumbered to those the patches use, in order of first use.
void drop_unused_vertices(radfmt::MeshData& mesh) {
    std::vector<std::uint32_t> new_id(mesh.vertices.size(), surfaces::kNone);
    std::vector<Vec3> kept;
    for (auto& p : mesh.patches)
        for (int k = 0; k < p.corner_count(); ++k) {
            auto& c = p.corners[k];
            if (new_id[c] == surfaces::kNone) {
                new_id[c] = static_cast<std::uint32_t>(kept.size());
                kept.push_back(mesh.vertices[c]);
            }
            c = new_id[c];
        }
    mesh.vertices = std::move(kept);
}

} // namespace

radfmt::MeshData mesh_surfaces(const radfmt::MeshData& faces, const SurfaceOptions& options,
                               SurfaceReport* report) {
    SurfaceReport local;
    SurfaceReport& rep = report ? *report : local;
    rep.faces = faces.patches.size();
    const auto weld = weld_by_position(faces.vertices);
    surfaces::Points points;
    const std::uint32_t count = weld.empty() ? 0 : *std::max_element(weld.begin(), weld.end()) + 1;
    points.position.assign(count, Vec3{});
    std::vector<bool> placed(count, false);
    for (std::size_t v = 0; v < faces.vertices.size(); ++v)
        if (!placed[weld[v]]) placed[weld[v]] = true, points.position[weld[v]] = faces.vertices[v];
    const double size = bounds(faces.vertices).diagonal();
    const double tolerance = 1e-7 * size;

    begin_stage(options.stages, "planar regions");
    auto regions = surfaces::find_planar_regions(faces, weld, points, options, size);
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
        surfaces::trace_outline(region, faces, weld, points);
        region.width = surfaces::region_width(region, points);
        region.piece = piece_length(region.cell, region.width);
    }
    begin_stage(options.stages, "outline runs");
    rep.regions = regions.size();
    rep.dropped_vertices = surfaces::split_outline_runs(regions, points, tolerance);
    begin_stage(options.stages, "outline refinement");
    surfaces::refine_outline_pieces(regions, points, tolerance, 6);
    begin_stage(options.stages, "grids");

    radfmt::MeshData mesh;
    mesh.groups = faces.groups;
    mesh.materials = faces.materials;
    std::vector<WidthClass> classes;
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const auto& region = regions[r];
        if (r % 1024 == 0) stage_fraction(options.stages, double(r) / regions.size());
        const double width = surfaces::grid_region(region, points, mesh, rep, tolerance);
        // Regions thinner than a tenth of a cell are slivers by their own shape; those under a
        // cell are cut across into near-square patches.
        classes.resize(mesh.patches.size(), width_class(region.cell, width));
    }
    mesh.vertices = points.position;
    rep.shape = shape_stats(mesh, classes);
    drop_unused_vertices(mesh);
    if (mesh.patches.size() >= radfmt::kNoVertex)
        throw InputError("too many patches for 32-bit indices");
    return mesh;
}

double patch_aspect(const radfmt::MeshData& mesh, const radfmt::Patch& patch) {
    const int n = patch.corner_count();
    std::array<Vec3, 4> c;
    for (int k = 0; k < n; ++k) c[k] = mesh.vertices[patch.corners[k]];
    double longest = 0;
    std::array<double, 4> side{};
    for (int k = 0; k < n; ++k) {
        side[k] = length(c[(k + 1) % n] - c[k]);
        longest = std::max(longest, side[k]);
    }
    if (!(patch.area > 0)) return 1e300;
    if (n == 3) return longest * longest / (2 * patch.area);
    // A quad's heights: its area over the mean length of each pair of opposite sides.
    const double h1 = patch.area / std::max(1e-300, 0.5 * (side[0] + side[2]));
    const double h2 = patch.area / std::max(1e-300, 0.5 * (side[1] + side[3]));
    return longest / std::min(h1, h2);
}

ShapeStats shape_stats(const radfmt::MeshData& mesh, const std::vector<WidthClass>& classes) {
    ShapeStats stats;
    std::size_t good[2] = {0, 0}, counted[2] = {0, 0};
    stats.worst_aspect = 0;
    for (std::size_t k = 0; k < mesh.patches.size(); ++k) {
        const auto c = k < classes.size() ? classes[k] : WidthClass::Wide;
        if (c == WidthClass::Thin) {
            ++stats.thin;
            continue;
        }
        const double a = patch_aspect(mesh, mesh.patches[k]);
        const bool fine = a <= 3;
        ++counted[0], good[0] += fine; // a tenth of a cell wide or more
        if (c == WidthClass::Wide) ++counted[1], good[1] += fine;
        stats.worst_aspect = std::max(stats.worst_aspect, a);
    }
    stats.fraction_aspect_at_most_3 = counted[0] ? double(good[0]) / double(counted[0]) : 1;
    stats.fraction_wide_aspect_at_most_3 = counted[1] ? double(good[1]) / double(counted[1]) : 1;
    return stats;
}

} // namespace rad
