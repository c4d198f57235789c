// The patch pass: the scene's faces cleaned (planar triangles and quads), then gridded as
// planar regions (or, --surfaces faces, each face subdivided on its own).
#include "radiosity/build_mesh.hpp"
#include "radiosity/error.hpp"
#include "radiosity/stages.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rad {

namespace {

SurfaceOptions surface_options(const SubdivisionOptions& limits, const std::string& source,
                               StageLog* stages) {
    SurfaceOptions options;
    options.max_edge = limits.max_edge;
    options.max_area = limits.max_area;
    options.max_edge_by_group = limits.max_edge_by_group;
    options.max_area_by_group = limits.max_area_by_group;
    options.max_patches = limits.max_patches;
    options.max_sag = limits.max_sag;
    options.source = source;
    options.stages = stages;
    return options;
}

void report_faces(const Scene& scene, const SubdivisionReport& faces, MeshReport& report) {
    if (faces.nonplanar_split) {
        // An OBJ's line, or a glTF/assimp face by its node and mesh.
        const auto worst = scene.face_ranges.empty()
                               ? "line " + std::to_string(faces.worst_nonplanar_line)
                               : face_number(scene, faces.worst_nonplanar_line);
        char text[256];
        std::snprintf(text, sizeof text,
                      ": %.3g off its plane, %.2g%% of its size; --strict refuses them)",
                      faces.worst_nonplanar_offset, 100 * faces.worst_nonplanar_relative);
        report.add(MeshReport::Kind::Change,
                   "triangulated: " + std::to_string(faces.nonplanar_split) +
                       " non-planar face(s) split into triangles (worst at " + worst + text);
    }
    if (faces.degenerate_dropped)
        report.add(MeshReport::Kind::Change,
                   "dropped: " + std::to_string(faces.degenerate_dropped) +
                       " degenerate (zero-area) face(s)");
}

// Regions of faces drawn partly over each other, meshed as what they cover.
void report_overlaps(const SurfaceReport& surfaces, MeshReport& report) {
    if (!surfaces.overlapped_regions) return;
    char text[300];
    std::snprintf(text, sizeof text,
                  "merged: %zu planar region(s) of faces drawn partly over each other meshed as "
                  "the area they cover, %.6g less than the faces' sum (--surfaces faces keeps "
                  "every face)",
                  surfaces.overlapped_regions, surfaces.overlap_area);
    report.add(MeshReport::Kind::Change, text);
}

// Ground the regions covered where other surfaces rise from them.
void report_growth(const SurfaceReport& surfaces, MeshReport& report) {
    if (!surfaces.holes_filled && !surfaces.bends_cut) return;
    char text[400];
    std::snprintf(text, sizeof text,
                  "covered: %zu hole(s) under a tenth of a cell across filled and %zu corner(s) "
                  "of short steps cut off, where other surfaces rise from the region (a pipe "
                  "through it, a pillar's foot): area %.6g gained under or inside them, saving "
                  "patches the size of the steps (--surfaces faces keeps every face)",
                  surfaces.holes_filled, surfaces.bends_cut, surfaces.area_covered);
    report.add(MeshReport::Kind::Change, text);
}

// Thin facets of curved surfaces taken as planar faces across them.
void report_strips(const StripMerge& strips, double max_sag, MeshReport& report) {
    if (!strips.faces) return;
    char text[500];
    std::snprintf(text, sizeof text,
                  "merged: %zu thin facet(s) of %zu curved surface(s) (long, under a tenth of a "
                  "cell wide: slivers as drawn) taken as %zu planar face(s) across them, each "
                  "within %.3g%% of a cell of the facets' edges (at most %.3g off); their "
                  "area %.6g for the facets' %.6g (--max-sag 0 keeps the facets)",
                  strips.facets, strips.chains, strips.faces, 100 * max_sag, strips.worst_offset,
                  strips.area_after, strips.area_before);
    report.add(MeshReport::Kind::Change, text);
}

// The default limit: the scene's size over kSceneCells (the diagonal of the used vertices'
// bounding box), or the edge of a square of the surfaces' area over the patch budget where
// that is smaller (a long or flat scene).
SubdivisionOptions resolve_limits(const Scene& scene, SubdivisionOptions limits,
                                  MeshReport& report) {
    if (limits.max_edge != kMaxEdgeFromScene) return limits;
    Box box;
    double area = 0;
    std::vector<Vec3> points;
    for (const auto& polygon : scene.polygons) {
        points.clear();
        for (const auto v : polygon.vertices) {
            box.add(scene.vertices[v]);
            points.push_back(scene.vertices[v]);
        }
        area += 0.5 * length(newell_normal(points));
    }
    const double from_size = box.diagonal() / kSceneCells;
    const double from_area = std::sqrt(area / limits.patch_budget);
    char text[400];
    if (from_area < from_size) {
        limits.max_edge = from_area;
        std::snprintf(text, sizeof text,
                      "--max-edge %.4g (the surfaces' area %.4g over %g patches: the scene is "
                      "long or flat, its size %.4g / %g would be %.4g; --patches N sets the "
                      "budget, --max-edge L the edge, --max-edge none keeps surfaces whole)",
                      limits.max_edge, area, limits.patch_budget, box.diagonal(), kSceneCells,
                      from_size);
    } else {
        limits.max_edge = from_size;
        std::snprintf(text, sizeof text,
                      "--max-edge %.4g (the scene's size %.4g / %g: about %g patches across it; "
                      "--max-edge L sets it, --max-edge none keeps surfaces whole)",
                      limits.max_edge, box.diagonal(), kSceneCells, kSceneCells);
    }
    report.add(MeshReport::Kind::Note, text);
    return limits;
}

} // namespace

radfmt::MeshData patch_pass(Scene& scene, const MeshOptions& options, MeshReport& report) {
    const auto limits = resolve_limits(scene, options.subdivision, report);
    for (const auto* by_group : {&limits.max_edge_by_group, &limits.max_area_by_group})
        for (const auto& [group, value] : *by_group)
            if (std::find(scene.groups.begin(), scene.groups.end(), group) == scene.groups.end())
                throw InputError("no group '" + group + "' in " + scene.path);
    SubdivisionReport faces;
    radfmt::MeshData mesh;
    report.regions = options.regions;
    if (options.regions) {
        begin_stage(options.scene.stages, "faces"); // cleaned first, gridded as regions
        const auto clean = clean_faces(scene, limits, &faces);
        auto surface = surface_options(limits, scene.path, options.scene.stages);
        surface.creases = scene.contact_lines;
        mesh = mesh_surfaces(clean, surface, &report.surfaces);
    } else {
        begin_stage(options.scene.stages, "patches");
        mesh = subdivide(scene, limits, &faces);
    }
    report_faces(scene, faces, report);
    report_strips(report.surfaces.strips, limits.max_sag, report);
    report_overlaps(report.surfaces, report);
    report_growth(report.surfaces, report);
    return mesh;
}

} // namespace rad
