// rad-mesh: OBJ+MTL scene -> conforming patch mesh.
#include "radfmt/chain.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/coincident.hpp"
#include "radiosity/error.hpp"
#include "radiosity/materials.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/orientation.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/surfaces.hpp"
#include "radiosity/two_sided.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <algorithm>
#include <cmath>

#include <cstdio>
#include <functional>
#include <iostream>

namespace {
// "0.25" sets the default; "floor=0.1" sets the limit of one group.
void parse_limits(const std::vector<std::string>& specs, const char* option, double& fallback,
                  std::map<std::string, double>& by_group) {
    for (const auto& spec : specs) {
        const auto eq = spec.rfind('=');
        const std::string number = eq == std::string::npos ? spec : spec.substr(eq + 1);
        double value = 0;
        if (!rad::parse_number(number, value))
            throw rad::InputError(std::string(option) + ": '" + spec +
                                  "' is not a number or GROUP=number");
        if (!(value > 0))
            throw rad::InputError(std::string(option) + ": '" + spec + "' must be positive");
        if (eq == std::string::npos)
            fallback = value;
        else
            by_group[spec.substr(0, eq)] = value;
    }
}
// One line per kind of coincident faces: how many, their area and the first lines.
void report_coincident(const rad::CoincidentReport& report, std::vector<std::string>& changes,
                       const std::function<void(const std::string&)>& warn) {
    using Case = rad::CoincidentCase;
    for (const auto kind : {Case::kMerged, Case::kWrongCopy, Case::kTwins, Case::kUndecided}) {
        std::size_t count = 0;
        double area = 0;
        std::string lines;
        for (const auto& c : report.cases) {
            if (c.kind != kind) continue;
            if (count < 6 && c.other_line > 0)
                lines += (count ? ", " : "") + std::to_string(c.other_line) +
                         (kind == Case::kMerged || kind == Case::kWrongCopy ? " (copy of "
                                                                            : " (twin of ") +
                         std::to_string(c.kept_line) + ")";
            ++count;
            area += c.area;
        }
        if (!count) continue;
        if (count > 6 && !lines.empty()) lines += ", ...";
        lines = lines.empty() ? "" : ", line " + lines;
        char head[200];
        std::snprintf(head, sizeof head, "%zu face(s) of area %.6g ", count, area);
        switch (kind) {
        case Case::kMerged:
            changes.push_back(std::string("coincident: dropped ") + head +
                              "lying within a face of the same plane and winding" + lines);
            break;
        case Case::kWrongCopy:
            changes.push_back(std::string("coincident: dropped ") + head +
                              "drawn again facing the other way whose side sees backs or nothing "
                              "(the copy facing the scene is kept)" +
                              lines);
            break;
        case Case::kTwins:
            changes.push_back(std::string("coincident: kept ") + head +
                              "drawn both ways, both sides facing the scene, as the two sides of "
                              "a sheet" +
                              lines);
            break;
        case Case::kUndecided:
            warn(std::string("coincident: ") + head +
                 "drawn both ways; their rays do not tell which side faces the scene, both are "
                 "kept (--flip GROUP, or delete one copy)" +
                 lines);
            break;
        }
    }
}
} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Read a scene (Wavefront OBJ with its MTL materials: Kd = reflectance, Ke = "
                 "emitted exitance in W/m^2;\nor glTF, PLY, COLLADA, FBX) and write the conforming "
                 "patch mesh of the chain."};
    std::string input, output;
    std::vector<std::string> max_edge, max_area;
    double planarity = 1e-3;
    bool quiet = false;
    app.add_option("SCENE", input,
                   "Scene file: OBJ (+ MTL), or glTF 2.0 (.gltf, .glb), PLY, COLLADA (.dae), "
                   "FBX and the other formats assimp reads")
        ->required();
    app.add_option("-o,--output", output, "Output mesh file")->required();
    app.add_option("--max-edge", max_edge,
                   "Longest patch edge; repeat as GROUP=L for a per-group limit (default: no "
                   "subdivision)");
    app.add_option("--max-area", max_area, "Largest patch area; repeat as GROUP=A per group");
    double max_patches = 2e7;
    app.add_option("--max-patches", max_patches,
                   "Refuse (before subdividing) when the limits would make more patches than "
                   "this")
        ->capture_default_str()
        ->check(rad::tool::finite_range(1, 4e9));
    app.add_option("--planarity-tolerance", planarity,
                   "Largest distance of a face vertex from the face's plane, relative to the "
                   "face's size")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1));
    std::string patch_order = "morton";
    app.add_option("--patch-order", patch_order,
                   "How patches are numbered: morton (along a Z-order curve of their centroids, "
                   "so that neighbours in space are neighbours in memory: faster solves) or "
                   "faces (in the order of the scene's faces, each face's patches row by row)")
        ->capture_default_str()
        ->check(CLI::IsMember({"morton", "faces"}));
    bool strict = false;
    rad::SceneOptions obj_options;
    std::string default_reflectance;
    std::vector<std::string> mtl_paths;
    app.add_flag("--strict", strict,
                 "Refuse what is otherwise repaired with a warning: non-planar faces (split "
                 "into triangles), faces without a known material (given a default one), "
                 "missing material libraries");
    app.add_option("--default-reflectance", default_reflectance,
                   "Reflectance of the material given to faces without one: r,g,b or one value "
                   "(default: 0.5)");
    app.add_option("--emission-scale", obj_options.emission_scale,
                   "glTF, PLY, COLLADA, FBX: W/m^2 of emission per unit of emissive colour x "
                   "emissiveStrength (their emission has no physical unit)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1e30));
    app.add_option("--mtl-path", mtl_paths,
                   "Folder to look for material libraries in, after the OBJ's folder and the "
                   "current directory (repeatable)");
    std::string orient = "warn";
    std::vector<std::string> flip;
    app.add_option("--orient", orient,
                   "Faces that point the wrong way (against their vn, against their neighbours, "
                   "closed objects inside out): warn about them, or fix them (consistent within "
                   "each connected surface, closed objects outward, then open surfaces whose "
                   "back sees the front of others flipped by ray-cast voting)")
        ->capture_default_str()
        ->check(CLI::IsMember({"warn", "fix"}));
    app.add_option("--flip", flip, "Reverse the faces of this group (repeatable)");
    std::vector<std::string> two_sided;
    bool two_sided_emission = false;
    app.add_option("--two-sided", two_sided,
                   "Give these surfaces a back patch per patch, with its own radiosity, for "
                   "thin things modelled as one sheet (curtains, leaves, table tops as "
                   "planes): a group name, a material name, or 'all' (repeatable)");
    app.add_flag("--two-sided-emission", two_sided_emission,
                 "Emitters among the --two-sided surfaces emit from both sides (default: the "
                 "front only; the back gets the material's copy '<name>.back' without Ke)");
    bool no_imprint = false;
    app.add_flag("--no-imprint", no_imprint,
                 "Do not imprint contacts (by default, where another object touches or crosses "
                 "a face, the contact lines are cut into it before subdividing, so no patch "
                 "straddles a contact, and regions hidden inside other geometry are removed)");
    std::string surfaces = "regions";
    app.add_option("--surfaces", surfaces,
                   "What is gridded into patches: regions (connected faces in one plane with one "
                   "material and group are merged into one surface, gridded into near-square "
                   "patches along its own axes, whatever the input's triangulation) or faces "
                   "(each input face subdivided on its own: the input's triangulation shows)")
        ->capture_default_str()
        ->check(CLI::IsMember({"regions", "faces"}));
    app.add_flag("-q,--quiet", quiet, "Print no summary");
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::tool::run_tool("rad-mesh", [&] {
        rad::tool::check_outputs({input}, {{"-o", output}});
        rad::SubdivisionOptions options;
        parse_limits(max_edge, "--max-edge", options.max_edge, options.max_edge_by_group);
        parse_limits(max_area, "--max-area", options.max_area, options.max_area_by_group);
        options.planarity_tolerance = planarity;
        options.strict = strict;
        options.max_patches = max_patches;
        obj_options.strict = strict;
        for (const auto& dir : mtl_paths) obj_options.mtl_paths.emplace_back(dir);
        if (!default_reflectance.empty()) {
            const auto value = rad::parse_material_override("default=" + default_reflectance,
                                                            "--default-reflectance")
                                   .value;
            for (double v : value)
                if (!(v < 1))
                    throw rad::InputError("--default-reflectance: " + default_reflectance +
                                          " has a channel >= 1 (a reflectance is below 1)");
            obj_options.default_reflectance = value;
        }
        const auto warn = [&](const std::string& text) {
            std::cerr << "rad-mesh: warning: " << input << ": " << text << '\n';
        };
        // What was repaired, one line per kind, printed after the summary (and even with
        // --quiet: the mesh differs from the file).
        std::vector<std::string> changes;
        rad::SceneReport obj_report;
        auto scene = rad::load_scene(input, obj_options, &obj_report);
        {
            std::vector<radfmt::Vec3> used; // unused vertices do not count
            for (const auto& polygon : scene.polygons)
                for (const auto v : polygon.vertices) used.push_back(scene.vertices[v]);
            rad::check_ray_precision(used, input);
        }
        for (const auto& lib : obj_report.libraries_found_by_name)
            changes.push_back("material library " + lib +
                              " (found by its file name; its folders do not exist here)");
        for (const auto& lib : obj_report.missing_libraries)
            warn("material library " + lib + " (--mtl-path DIR adds a folder)");
        if (!obj_report.unknown_materials.empty()) {
            std::string names;
            for (const auto& m : obj_report.unknown_materials)
                names += (names.empty() ? "" : ", ") + m;
            warn("material(s) not defined in any material library: " + names);
        }
        for (const auto& problem : obj_report.texture_problems)
            warn(problem + " (the material keeps its Kd)");
        if (obj_report.faces_defaulted) {
            std::string text = "defaulted: " + std::to_string(obj_report.faces_defaulted) +
                               " face(s) without a known material (first at line " +
                               std::to_string(obj_report.first_defaulted_line) +
                               ") got the default reflectance " +
                               rad::rgb_text(obj_options.default_reflectance) +
                               ", each under its own usemtl name where it has one (material '" +
                               (obj_report.default_material.empty() ? std::string("default")
                                                                    : obj_report.default_material) +
                               "' otherwise; --default-reflectance changes it, --strict refuses)";
            changes.push_back(std::move(text));
        }
        if (!obj_report.textures_averaged.empty()) {
            std::string text =
                "textures averaged: " + std::to_string(obj_report.textures_averaged.size()) +
                " map_Kd texture(s) multiply their Kd by their mean linear colour";
            if (!obj_report.textures_replacing_kd.empty()) {
                text += "; replacing a Kd of 0 or none in";
                for (const auto& m : obj_report.textures_replacing_kd) text += " " + m;
            }
            changes.push_back(std::move(text));
        }
        if (const auto duplicates = rad::remove_duplicate_faces(scene); duplicates.removed) {
            std::string lines;
            for (std::size_t k = 0; k < duplicates.lines.size() && k < 10; ++k)
                lines += (k ? ", " : "") + std::to_string(duplicates.lines[k].first) +
                         " (repeats " + std::to_string(duplicates.lines[k].second) + ")";
            if (duplicates.lines.size() > 10) lines += ", ...";
            std::string text = "deduplicated: dropped " + std::to_string(duplicates.removed) +
                               " duplicate face(s), line " + lines;
            changes.push_back(std::move(text));
        }
        if (!flip.empty()) {
            const auto count = rad::flip_groups(scene, flip);
            if (!quiet) std::cerr << "rad-mesh: --flip reversed " << count << " face(s)\n";
        }
        const auto findings = rad::check_orientation(scene);
        for (const auto& finding : findings)
            std::cerr << "rad-mesh: warning: " << input << ": " << rad::describe(finding, scene)
                      << (orient == "fix" || finding.to_flip.empty()
                              ? ""
                              : "; --orient fix would flip them, or --flip the group")
                      << '\n';
        if (orient == "fix") {
            for (const auto& [group, count] : rad::fix_orientation(scene, findings))
                std::cerr << "rad-mesh: --orient fix flipped " << count << " face(s) of group "
                          << group << '\n';
            // With closed objects facing outward, rays tell which way open surfaces face.
            const auto facing = rad::check_facing_by_visibility(scene);
            for (const auto& finding : facing)
                std::cerr << "rad-mesh: warning: " << input << ": " << rad::describe(finding, scene)
                          << '\n';
            for (const auto& [group, count] : rad::fix_orientation(scene, facing))
                std::cerr << "rad-mesh: --orient fix flipped " << count << " face(s) of group "
                          << group << " (visibility)\n";
        }
        report_coincident(rad::resolve_coincident_faces(scene), changes, warn);
        for (const auto* by_group : {&options.max_edge_by_group, &options.max_area_by_group})
            for (const auto& [group, value] : *by_group)
                if (std::find(scene.groups.begin(), scene.groups.end(), group) ==
                    scene.groups.end())
                    throw rad::InputError("no group '" + group + "' in " + input);
        if (!no_imprint) {
            // Hidden regions are judged with the faces turned as --orient fix would turn them.
            std::vector<bool> turned(scene.polygons.size(), false);
            // Only the findings that are safe to act on: a closed room facing out, and faces
            // wound against the rest of their surface ("inside out" can be a room that does
            // not enclose everything: a beam sticking out through its wall).
            using Kind = rad::OrientationFinding::Kind;
            if (orient != "fix")
                for (const auto& finding : findings)
                    if (finding.kind == Kind::RoomOutward ||
                        finding.kind == Kind::AgainstNeighbours)
                        for (const auto f : finding.to_flip) turned[f] = !turned[f];
            std::map<std::uint32_t, double> group_area;
            for (const auto& polygon : scene.polygons) {
                std::vector<radfmt::Vec3> pts;
                for (const auto v : polygon.vertices) pts.push_back(scene.vertices[v]);
                group_area[polygon.group] += 0.5 * rad::length(rad::newell_normal(pts));
            }
            const auto imprint = rad::imprint_contacts(scene, 1e-7, turned);
            for (const auto& [group, area] : imprint.removed_by_group)
                if (area > 0.01 * group_area[group]) {
                    char text[300];
                    std::snprintf(text, sizeof text,
                                  "imprinting removed %.6g of group %s's area %.6g (%.1f%%), "
                                  "reaching the faces' own outlines, as hidden inside or "
                                  "behind other geometry; if that is wrong, "
                                  "check which way the surfaces around it face (--orient fix) "
                                  "or use --no-imprint",
                                  area, scene.groups[group].c_str(), group_area[group],
                                  100 * area / group_area[group]);
                    warn(text);
                }
            if (imprint.faces_imprinted) {
                char text[300];
                std::snprintf(text, sizeof text,
                              "imprinted: contacts cut into %zu face(s) (area %.6g); %zu hidden "
                              "region(s) removed (area %.6g)",
                              imprint.faces_imprinted, imprint.area_imprinted,
                              imprint.regions_removed, imprint.area_removed);
                std::string line = text;
                if (!imprint.removed_lines.empty()) {
                    line += ", from the face(s) at line";
                    for (std::size_t k = 0; k < imprint.removed_lines.size() && k < 8; ++k)
                        line += " " + std::to_string(imprint.removed_lines[k]);
                    if (imprint.removed_lines.size() > 8) line += " ...";
                }
                line += " (--no-imprint keeps the faces whole)";
                changes.push_back(std::move(line));
            }
        }
        rad::SubdivisionReport report;
        rad::SurfaceReport surface_report;
        radfmt::MeshData mesh;
        if (surfaces == "regions") {
            rad::SubdivisionOptions whole = options; // clean faces first, gridded as regions
            whole.max_edge = whole.max_area = 0;
            whole.max_edge_by_group.clear();
            whole.max_area_by_group.clear();
            rad::SurfaceOptions surface_options;
            surface_options.max_edge = options.max_edge;
            surface_options.max_area = options.max_area;
            surface_options.max_edge_by_group = options.max_edge_by_group;
            surface_options.max_area_by_group = options.max_area_by_group;
            surface_options.max_patches = options.max_patches;
            surface_options.source = input;
            mesh = rad::mesh_surfaces(rad::subdivide(scene, whole, &report), surface_options,
                                      &surface_report);
        } else {
            mesh = rad::subdivide(scene, options, &report);
        }
        if (report.nonplanar_split) {
            char text[256];
            std::snprintf(text, sizeof text,
                          "triangulated: %zu non-planar face(s) split into triangles (worst at "
                          "line %d: %.3g off its plane, %.2g%% of its size; --strict refuses "
                          "them)",
                          report.nonplanar_split, report.worst_nonplanar_line,
                          report.worst_nonplanar_offset, 100 * report.worst_nonplanar_relative);
            changes.emplace_back(text);
        }
        if (report.degenerate_dropped)
            changes.push_back("dropped: " + std::to_string(report.degenerate_dropped) +
                              " degenerate (zero-area) face(s)");
        if (two_sided_emission && two_sided.empty())
            throw rad::InputError("--two-sided-emission needs --two-sided GROUP|MATERIAL|all");
        if (!two_sided.empty()) {
            const auto sides = rad::make_two_sided(mesh, two_sided, two_sided_emission);
            if (!quiet)
                std::cerr << "rad-mesh: --two-sided added " << sides.back_patches
                          << " back patch(es)\n";
            for (const auto& name : sides.unlit_back_materials)
                if (!quiet)
                    std::cerr << "rad-mesh: the back of emitting material " << name
                              << " does not emit (material " << name
                              << ".back; --two-sided-emission to change)\n";
        }
        if (const auto problems = rad::material_warnings(mesh, scene.material_sources);
            !problems.empty()) {
            std::string text = "materials to check before solving:";
            for (const auto& line : problems) text += "\n  " + line;
            warn(text);
        }

        if (patch_order == "morton") rad::order_patches_by_locality(mesh);

        std::vector<radfmt::Parent> sources{{input, nullptr}};
        for (const auto& mtl : scene.material_files) sources.push_back({mtl, nullptr});
        const auto header = radfmt::derived_header(rad::tool_version("rad-mesh"),
                                                   radfmt::command_line(argc, argv), sources);
        radfmt::write_mesh(output, header, mesh);
        if (!quiet) {
            const auto topo = rad::analyze_topology(mesh);
            std::fprintf(
                stderr, "rad-mesh: %zu patches, %zu vertices, total area %.9g, %zu open edges%s\n",
                mesh.patches.size(), mesh.vertices.size(), mesh.total_area(), topo.boundary_edges,
                topo.rejected_patches ? " (non-manifold parts present)" : "");
            if (surfaces == "regions") {
                const auto& shape = surface_report.shape;
                std::fprintf(stderr,
                             "rad-mesh: %zu face(s) as %zu planar region(s): %zu grid cell(s), "
                             "%zu triangle(s) along outlines; aspect <= 3: %.1f%% of the patches "
                             "of regions a cell wide or more (worst %.3g), %zu patch(es) in "
                             "thinner regions\n",
                             surface_report.faces, surface_report.regions, surface_report.cells,
                             surface_report.band_triangles, 100 * shape.fraction_aspect_at_most_3,
                             shape.worst_aspect, shape.excused);
            }
        }
        for (const auto& change : changes) std::cerr << "rad-mesh: changed: " << change << '\n';
        return 0;
    });
}
