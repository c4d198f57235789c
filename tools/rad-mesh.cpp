// rad-mesh: OBJ+MTL scene -> conforming patch mesh.
#include "radfmt/chain.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/orientation.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/two_sided.hpp"
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
} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Read a Wavefront OBJ scene with its MTL materials (Kd = reflectance, Ke = "
                 "emitted exitance in W/m^2)\nand write the conforming patch mesh of the chain."};
    std::string input, output;
    std::vector<std::string> max_edge, max_area;
    double planarity = 1e-3;
    bool quiet = false;
    app.add_option("SCENE", input, "OBJ file")->required();
    app.add_option("-o,--output", output, "Output mesh file")->required();
    app.add_option("--max-edge", max_edge,
                   "Longest patch edge; repeat as GROUP=L for a per-group limit (default: no "
                   "subdivision)");
    app.add_option("--max-area", max_area, "Largest patch area; repeat as GROUP=A per group");
    app.add_option("--planarity-tolerance", planarity,
                   "Largest distance of a face vertex from the face's plane, relative to the "
                   "face's size")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1));
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
    app.add_flag("-q,--quiet", quiet, "Print no summary");
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::tool::run_tool("rad-mesh", [&] {
        rad::SubdivisionOptions options;
        parse_limits(max_edge, "--max-edge", options.max_edge, options.max_edge_by_group);
        parse_limits(max_area, "--max-area", options.max_area, options.max_area_by_group);
        options.planarity_tolerance = planarity;
        auto scene = rad::load_obj(input);
        if (const auto duplicates = rad::remove_duplicate_faces(scene); duplicates.removed)
            std::cerr << "rad-mesh: warning: " << input << ": dropped " << duplicates.removed
                      << " duplicate face(s) (first at line " << duplicates.first_line
                      << ", a repeat of line " << duplicates.first_original_line << ")\n";
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
        for (const auto* by_group : {&options.max_edge_by_group, &options.max_area_by_group})
            for (const auto& [group, value] : *by_group)
                if (std::find(scene.groups.begin(), scene.groups.end(), group) ==
                    scene.groups.end())
                    throw rad::InputError("no group '" + group + "' in " + input);
        rad::SubdivisionReport report;
        auto mesh = rad::subdivide(scene, options, &report);
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
        if (report.degenerate_dropped)
            std::cerr << "rad-mesh: warning: " << input << ": dropped " << report.degenerate_dropped
                      << " degenerate (zero-area) face(s)\n";

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
        }
        return 0;
    });
}
