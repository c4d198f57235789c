// The load pass: the scene read (OBJ+MTL or assimp), what its reader repaired or missed.
#include "radiosity/build_mesh.hpp"
#include "radiosity/material_overrides.hpp"
#include "radiosity/materials.hpp"
#include "radiosity/rays.hpp"

namespace rad {

namespace {

// Many materials may name textures that are not there (a game map without its packages):
// one line for all of them, with the first few.
void report_texture_problems(const SceneReport& scene, MeshReport& report) {
    constexpr std::size_t kListed = 4;
    const auto& problems = scene.texture_problems;
    if (problems.size() <= kListed) {
        for (const auto& problem : problems)
            report.add(MeshReport::Kind::Warning, problem + " (the material keeps its Kd)");
        return;
    }
    std::string text = std::to_string(problems.size()) +
                       " materials' textures are missing or unreadable (they keep their Kd): ";
    for (std::size_t k = 0; k < kListed; ++k) text += (k ? "; " : "") + problems[k];
    report.add(MeshReport::Kind::Warning, text + "; ...");
}

void report_materials(const SceneReport& scene, const SceneOptions& options, MeshReport& report) {
    using Kind = MeshReport::Kind;
    for (const auto& lib : scene.libraries_found_by_name)
        report.add(Kind::Change, "material library " + lib +
                                     " (found by its file name; its folders do not exist here)");
    for (const auto& lib : scene.missing_libraries)
        report.add(Kind::Warning, "material library " + lib + " (--mtl-path DIR adds a folder)");
    if (!scene.unknown_materials.empty()) {
        std::string names;
        for (const auto& m : scene.unknown_materials) names += (names.empty() ? "" : ", ") + m;
        report.add(Kind::Warning, "material(s) not defined in any material library: " + names);
    }
    report_texture_problems(scene, report);
    if (!scene.lights.empty()) {
        std::string text = std::to_string(scene.lights.size()) +
                           " light(s) of the file are not surfaces and light nothing here:";
        for (std::size_t k = 0; k < scene.lights.size() && k < 4; ++k)
            text += (k ? ", " : " ") + scene.lights[k];
        if (scene.lights.size() > 4) text += ", ...";
        report.add(Kind::Warning,
                   text + "; put a luminaire at each (rad-ff --luminaires LAYOUT, a row with its "
                          "x, y, z and an IES or LDT file), or give a surface an emission "
                          "(rad-solve --emission NAME=r,g,b)");
    }
    for (const auto& line : scene.materials_read) report.add(Kind::Note, line);
    for (const auto& line : scene.materials_changed) report.add(Kind::Change, line);
    if (scene.dangling_corners)
        report.add(Kind::Change, "ignored: " + std::to_string(scene.dangling_corners) +
                                     " face corner(s) name a texture coordinate or normal that "
                                     "does not exist (first at " +
                                     scene.first_dangling +
                                     "); neither shapes a patch (--strict refuses)");
    if (scene.faces_defaulted)
        report.add(
            Kind::Change,
            "defaulted: " + std::to_string(scene.faces_defaulted) +
                " face(s) without a known material (first at line " +
                std::to_string(scene.first_defaulted_line) + ") got the default reflectance " +
                rgb_text(options.default_reflectance) +
                ", each under its own usemtl name where it has one (material '" +
                (scene.default_material.empty() ? std::string("default") : scene.default_material) +
                "' otherwise; --default-reflectance changes it, --strict refuses)");
    if (!scene.textures_averaged.empty()) {
        std::string text = "textures averaged: " + std::to_string(scene.textures_averaged.size()) +
                           " map_Kd texture(s) multiply their Kd by their mean linear colour";
        if (!scene.textures_replacing_kd.empty()) {
            text += "; replacing a Kd of 0 or none in";
            for (const auto& m : scene.textures_replacing_kd) text += " " + m;
        }
        report.add(Kind::Change, text);
    }
}

} // namespace

Scene load_pass(const std::filesystem::path& input, const SceneOptions& options,
                MeshReport& report) {
    SceneReport scene_report;
    auto scene = load_scene(input, options, &scene_report);
    std::vector<radfmt::Vec3> used; // unused vertices do not count
    for (const auto& polygon : scene.polygons)
        for (const auto v : polygon.vertices) used.push_back(scene.vertices[v]);
    check_ray_precision(used, input.string());
    for (const auto& m : scene.materials)
        check_emission_limit(m, input.string() + ": material '" + m.name + "'",
                             "check its value and unit (--emission-scale scales glTF, PLY, "
                             "COLLADA and FBX emission)");
    report_materials(scene_report, options, report);
    return scene;
}

} // namespace rad
