// rad-mesh: OBJ+MTL scene -> conforming patch mesh.
#include "radfmt/chain.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/build_mesh.hpp"
#include "radiosity/error.hpp"
#include "radiosity/huge_pages.hpp"
#include "radiosity/materials.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/stages.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <algorithm>
#include <cmath>

#include <cstdio>
#include <iostream>

namespace {
// "0.25" sets the default; "floor=0.1" sets the limit of one group.
void parse_limits(const std::vector<std::string>& specs, const char* option, double& fallback,
                  std::map<std::string, double>& by_group) {
    for (const auto& spec : specs) {
        const auto eq = spec.rfind('=');
        const std::string number = eq == std::string::npos ? spec : spec.substr(eq + 1);
        if (number == "none") { // no limit (surfaces whole), for the scene or one group
            if (eq == std::string::npos)
                fallback = 0;
            else
                by_group[spec.substr(0, eq)] = 0;
            continue;
        }
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
void print_summary(const radfmt::MeshData& mesh, const rad::MeshReport& report) {
    const auto topo = rad::analyze_topology(mesh);
    std::fprintf(stderr, "rad-mesh: %zu patches, %zu vertices, total area %.9g, %zu open edges%s\n",
                 mesh.patches.size(), mesh.vertices.size(), mesh.total_area(), topo.boundary_edges,
                 topo.rejected_patches ? " (non-manifold parts present)" : "");
    if (!report.regions) return;
    const auto& s = report.surfaces;
    std::fprintf(
        stderr,
        "rad-mesh: %zu face(s) as %zu planar region(s): %zu grid cell(s), %zu "
        "triangle(s) along outlines (and %zu quad(s) of a speck or a sliver joined with its "
        "neighbour; %zu more speck(s) joined with a neighbour into one patch, %zu of them "
        "polygons); aspect <= 3: %.1f%% of the patches where the "
        "region is a tenth of a cell thick or more (%.1f%% of those where it is a cell "
        "thick or more; worst %.3g), %zu patch(es) where it is thinner, %zu under a "
        "tenth of a cell beside an outline piece that short, %zu under a tenth of a "
        "cell elsewhere; %zu outline point(s) left out where smoothing stops "
        "(T-vertices)\n",
        s.faces, s.regions, s.cells, s.band_triangles, s.joined, s.specks_joined,
        mesh.polygon_count(), 100 * s.shape.fraction_aspect_at_most_3,
        100 * s.shape.fraction_wide_aspect_at_most_3, s.shape.worst_aspect, s.shape.thin,
        s.shape.specks_at_detail, s.shape.specks, s.t_vertices);
}
// What the command line says.
struct MeshArgs {
    std::string input, output;
    std::vector<std::string> max_edge, max_area;
    double patches = rad::kDefaultPatchBudget;
    CLI::Option* patches_option = nullptr;
    double planarity = 1e-3, max_patches = 2e7, max_sag = rad::kDefaultMaxSag;
    bool quiet = false, timings = false, strict = false;
    std::string patch_order = "morton", default_reflectance, orient = "warn";
    std::string surfaces = "regions", import_memory, unit = "m", max_memory;
    rad::SceneOptions scene;
    std::vector<std::string> mtl_paths, flip, two_sided, thin, transmittance;
    bool keep_lamps = false, verbose = false;
    bool two_sided_emission = false, no_imprint = false;
    double contact_gap = rad::kContactGap;
};

// The input, output and subdivision options.
void add_scene_options(CLI::App& app, MeshArgs& a) {
    app.add_option("SCENE", a.input,
                   "Scene file: OBJ (+ MTL), or glTF 2.0 (.gltf, .glb), PLY, COLLADA (.dae), "
                   "FBX and the other formats assimp reads")
        ->required();
    app.add_option("-o,--output", a.output, "Output mesh file")->required();
    app.add_option("--max-edge", a.max_edge,
                   "Longest patch edge, or none (surfaces as few patches as their shape "
                   "allows); repeat as GROUP=L for a per-group limit (default: the scene's "
                   "size, its bounding box's diagonal, over 20, or smaller for a long or flat "
                   "scene: see --patches)");
    app.add_option("--max-area", a.max_area, "Largest patch area; repeat as GROUP=A per group");
    a.patches_option =
        app.add_option("--patches", a.patches,
                       "Without --max-edge or --max-area: where the scene is long or flat "
                       "(the edge of a square of its surfaces' area over this many patches is "
                       "under its size / 20), patches of that edge, so a tunnel, a stairwell "
                       "and a cubic room of one area get patches of one size")
            ->capture_default_str()
            ->check(CLI::Range(1.0, 1e9));
    app.add_option("--unit", a.unit,
                   "The scene's length unit, recorded in the mesh: luminaires' candela become "
                   "lux through it (a scene drawn in millimetres: mm)")
        ->capture_default_str()
        ->check(CLI::IsMember({"m", "cm", "mm", "ft", "in"}));
    app.add_option("--max-patches", a.max_patches,
                   "Refuse (before subdividing) when the limits would make more patches than "
                   "this")
        ->capture_default_str()
        ->check(rad::tool::finite_range(1, 4e9));
    app.add_option("--planarity-tolerance", a.planarity,
                   "Largest distance of a face vertex from the face's plane, relative to the "
                   "face's size")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1));
    app.add_option("--max-sag", a.max_sag,
                   "A curved surface drawn as long thin facets (a vault, a column: under a tenth "
                   "of a cell wide, patches would be slivers) is taken as planar faces across "
                   "runs of them, each no wider than a cell and within this fraction of a cell "
                   "of every facet edge it spans, nor farther than a chord of an arc turning 30 "
                   "degrees (--surfaces regions; 0 keeps the facets)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 0.25));
    app.add_option("--patch-order", a.patch_order,
                   "How patches are numbered: morton (along a Z-order curve of their centroids, "
                   "so that neighbours in space are neighbours in memory: faster solves) or "
                   "faces (in the order of the scene's faces, each face's patches row by row)")
        ->capture_default_str()
        ->check(CLI::IsMember({"morton", "faces"}));
    app.add_flag("--strict", a.strict,
                 "Refuse what is otherwise repaired with a warning: non-planar faces (split "
                 "into triangles), faces without a known material (given a default one), "
                 "missing material libraries");
    app.add_option("--default-reflectance", a.default_reflectance,
                   "Reflectance of the material given to faces without one: r,g,b or one value "
                   "(default: 0.5)");
    app.add_option("--emission-scale", a.scene.emission_scale,
                   "glTF, PLY, COLLADA, FBX: W/m^2 of emission per unit of emissive colour x "
                   "emissiveStrength (their emission has no physical unit)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1e30));
    app.add_option("--mtl-path", a.mtl_paths,
                   "Folder to look for material libraries in, after the OBJ's folder and the "
                   "current directory (repeatable)");
}

// The mesh stage's own options: orientation, two-sided surfaces, imprinting, surfaces.
void add_stage_options(CLI::App& app, MeshArgs& a) {
    app.add_option("--orient", a.orient,
                   "Faces that point the wrong way (against their vn, against their neighbours, "
                   "closed objects inside out): warn about them, or fix them (consistent within "
                   "each connected surface, closed objects outward, then open surfaces whose "
                   "back sees the front of others flipped by ray-cast voting)")
        ->capture_default_str()
        ->check(CLI::IsMember({"warn", "fix"}));
    app.add_option("--flip", a.flip,
                   "Reverse the faces of this group, or of this material where no group has "
                   "the name (a file without groups), or, given as FILE:LINE of a face, its "
                   "connected surface (a vault sharing its material with the floor; repeatable)");
    app.add_option("--thin", a.thin,
                   "Make this refracting material (MTL illum 6 or 7, glTF volume), or the "
                   "refracting materials of this group, a thin pane of glass: light passes "
                   "without displacement, with the transmittance of a pane of its index, as "
                   "glazing drawn as one sheet should (repeatable)");
    app.add_option("--transmittance", a.transmittance,
                   "MATERIAL=r,g,b: what a glass material lets through instead of what its file "
                   "says (a pane: at normal incidence; a refracting solid: a passage through "
                   "it; MTL's Tf is that filter: Tf 0.1 lets a tenth through). 0 makes it "
                   "opaque; a value above 0 makes an opaque material a thin pane (repeatable)");
    app.add_flag("--keep-lamps", a.keep_lamps,
                 "Leave emitters as drawn: without it, an emitting material most of whose light "
                 "meets the back of surfaces (a lamp facing into its fixture) while its other "
                 "side's would not is turned, and said");
    app.add_option("--two-sided", a.two_sided,
                   "Give these surfaces a back patch per patch, with its own radiosity, for "
                   "thin things modelled as one sheet (curtains, leaves, table tops as "
                   "planes): a group name, a material name, or 'all' (repeatable)");
    app.add_flag("--two-sided-emission", a.two_sided_emission,
                 "Emitters among the --two-sided surfaces emit from both sides (default: the "
                 "front only; the back gets the material's copy '<name>.back' without Ke)");
    app.add_flag("--no-imprint", a.no_imprint,
                 "Do not imprint contacts (by default, where another object touches or crosses "
                 "a face, the contact lines are cut into it before subdividing, so no patch "
                 "straddles a contact, and regions hidden inside other geometry are removed)");
    app.add_option("--contact-gap", a.contact_gap,
                   "Imprinting: an edge of another object's face this far in front of a surface, "
                   "as a fraction of the scene's size (its bounding box's diagonal), touches it "
                   "when that face reaches 20 times as far out: a wall ending a hair below a "
                   "ceiling cuts it, so the ceiling's patches on each side see their own room "
                   "(0: only contacts within rounding)")
        ->default_val(rad::kContactGap)
        ->check(CLI::Range(0.0, 0.05));
    app.add_option("--surfaces", a.surfaces,
                   "What is gridded into patches: regions (connected faces in one plane with one "
                   "material and group are merged into one surface, gridded into near-square "
                   "patches along its own axes, whatever the input's triangulation) or faces "
                   "(each input face subdivided on its own: the input's triangulation shows)")
        ->capture_default_str()
        ->check(CLI::IsMember({"regions", "faces"}));
}

// Importing, textures, and what rad-mesh prints.
void add_import_options(CLI::App& app, MeshArgs& a) {
    app.add_option("--import-timeout", a.scene.import.seconds,
                   "glTF, PLY, COLLADA, FBX: assimp reads them in a process of its own; give up "
                   "on a file it has not read in this many seconds (0: no limit)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1e9));
    app.add_option("--import-memory", a.import_memory,
                   "... and on one for which it needs more address space than this (e.g. 4G; "
                   "default: 80% of what the job may use: physical memory, its cgroup limit or "
                   "ulimit -v, the least); a crash there is an error naming the "
                   "file, never the tool's");
    app.add_flag("--allow-outside-refs", a.scene.allow_outside_refs,
                 "Let the scene refer to files outside its own folder (material libraries, "
                 "textures, glTF buffers and images given by absolute paths or '..'); FIFOs "
                 "and devices are never opened");
    app.add_option("--max-texture-pixels", a.scene.max_texture_pixels,
                   "Textures with more pixels are not decoded (a warning; the material keeps "
                   "its Kd); each texture file is decoded once per run")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40));
    rad::tool::add_common_options(
        app, {.quiet = &a.quiet,
              .shows_progress = true,
              .verbose = &a.verbose,
              .verbose_help = "Every orientation warning line (without it, at most 20, those "
                              "with the most faces first, and a count of the rest)",
              .max_memory = &a.max_memory,
              .max_memory_refuses = "a scene whose faces (instances counted) are"});
    app.add_flag("--timings", a.timings,
                 "Print each stage's wall time and the peak memory so far (stderr), and "
                 "whether the heap is in transparent huge pages (rad-mesh restarts itself "
                 "once to ask glibc for them; RADIOSITY_HUGE_PAGES=0 keeps 4 KiB pages)");
}

// The mesh stage's options from the command line's (throws InputError on bad values).
rad::MeshOptions mesh_options_of(MeshArgs& a) {
    if (!a.import_memory.empty())
        a.scene.import.memory_bytes = rad::tool::parse_size(a.import_memory, "--import-memory");
    a.scene.max_memory = rad::tool::memory_limit(a.max_memory);
    rad::SubdivisionOptions options;
    // No limit given at all: one from the scene's size and area, chosen by the patch pass.
    if (a.max_edge.empty() && a.max_area.empty())
        options.max_edge = rad::kMaxEdgeFromScene;
    else if (a.patches_option->count() > 0)
        throw rad::InputError("--patches chooses the default patch size: not with --max-edge "
                              "or --max-area, which set it");
    options.patch_budget = a.patches;
    parse_limits(a.max_edge, "--max-edge", options.max_edge, options.max_edge_by_group);
    parse_limits(a.max_area, "--max-area", options.max_area, options.max_area_by_group);
    options.planarity_tolerance = a.planarity;
    options.strict = a.strict;
    options.max_patches = a.max_patches;
    options.max_sag = a.max_sag;
    a.scene.strict = a.strict;
    for (const auto& dir : a.mtl_paths) a.scene.mtl_paths.emplace_back(dir);
    if (!a.default_reflectance.empty()) {
        const auto value = rad::parse_material_override("default=" + a.default_reflectance,
                                                        "--default-reflectance")
                               .value;
        for (double v : value)
            if (!(v < 1))
                throw rad::InputError("--default-reflectance: " + a.default_reflectance +
                                      " has a channel >= 1 (a reflectance is below 1)");
        a.scene.default_reflectance = value;
    }
    rad::MeshOptions mesh_options;
    mesh_options.scene = a.scene;
    mesh_options.subdivision = options;
    mesh_options.regions = a.surfaces == "regions";
    mesh_options.imprint = !a.no_imprint;
    mesh_options.contact_gap = a.contact_gap;
    mesh_options.orient_fix = a.orient == "fix";
    mesh_options.turn_lamps = !a.keep_lamps;
    mesh_options.verbose = a.verbose;
    mesh_options.flip = a.flip;
    mesh_options.two_sided = a.two_sided;
    mesh_options.thin = a.thin;
    mesh_options.transmittance = a.transmittance;
    mesh_options.two_sided_emission = a.two_sided_emission;
    mesh_options.morton_order = a.patch_order == "morton";
    return mesh_options;
}

void print_lines(const rad::MeshReport& report, const std::string& input, bool quiet) {
    using Kind = rad::MeshReport::Kind;
    for (const auto& line : report.lines) {
        if (line.kind == Kind::Warning)
            std::cerr << "rad-mesh: warning: " << input << ": " << line.text << '\n';
        else if (line.kind == Kind::Fix || (line.kind == Kind::Note && !quiet))
            std::cerr << "rad-mesh: " << line.text << '\n';
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Read a scene (Wavefront OBJ with its MTL materials: Kd = reflectance, Ke = "
                 "emitted exitance in W/m^2;\nor glTF, PLY, COLLADA, FBX) and write the conforming "
                 "patch mesh of the chain."};
    MeshArgs a;
    add_scene_options(app, a);
    add_stage_options(app, a);
    add_import_options(app, a);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::restart_with_huge_pages(argv);

    return rad::tool::run_tool("rad-mesh", [&] {
        rad::tool::check_outputs({a.input}, {{"-o", a.output}});
        auto mesh_options = mesh_options_of(a);
        rad::StageLog stages("rad-mesh", a.quiet, a.timings);
        mesh_options.scene.stages = &stages;
        rad::MeshReport report;
        rad::Scene scene;
        const auto mesh = rad::build_mesh(a.input, mesh_options, report, &scene);
        stages.finish(); // clears the terminal's stage line before the report
        print_lines(report, a.input, a.quiet);

        stages.begin("writing " + std::filesystem::path(a.output).filename().string());
        std::vector<radfmt::Parent> sources{{a.input, nullptr}};
        for (const auto& mtl : scene.material_files) sources.push_back({mtl, nullptr});
        auto header = radfmt::derived_header(rad::tool_version("rad-mesh"),
                                             radfmt::command_line(argc, argv), sources);
        header.set("unit", a.unit);
        radfmt::write_mesh(a.output, header, mesh);
        stages.finish();
        if (a.timings) std::cerr << "rad-mesh: timing: pages: " << rad::huge_pages_state() << '\n';
        if (!a.quiet) print_summary(mesh, report);
        for (const auto& line : report.lines)
            if (line.kind == rad::MeshReport::Kind::Change)
                std::cerr << "rad-mesh: changed: " << line.text << '\n';
        return 0;
    });
}
