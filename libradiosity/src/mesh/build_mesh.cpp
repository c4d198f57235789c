// build_mesh: the passes of rad-mesh in order.
#include "radiosity/build_mesh.hpp"
#include "radiosity/error.hpp"
#include "radiosity/materials.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/stages.hpp"

#include <tbb/global_control.h>

namespace rad {

radfmt::MeshData build_mesh(const std::filesystem::path& input, const MeshOptions& options,
                            MeshReport& report, Scene* scene_out) {
    // One thread: the passes' ray casts (orientation, coincident faces, imprinting) are a
    // small part of the time, and results that depend on how work was shared between
    // threads (the ray scene's tree, which of two coincident faces a ray meets) would make
    // the mesh differ from machine to machine.
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    if (options.two_sided_emission && options.two_sided.empty())
        throw InputError("--two-sided-emission needs --two-sided GROUP|MATERIAL|all");
    StageLog* stages = options.scene.stages;
    begin_stage(stages, "reading " + input.filename().string());
    auto scene = load_pass(input, options.scene, report);
    check_mesh_memory(scene.polygons.size(), options.scene.max_memory, input.string());
    begin_stage(stages, "duplicates");
    duplicates_pass(scene, report);
    begin_stage(stages, "orientation");
    const auto turned = orientation_pass(scene, options, report);
    begin_stage(stages, "coincident faces");
    const auto kept = coincident_pass(scene, report);
    if (options.imprint) {
        begin_stage(stages, "imprinting");
        std::vector<bool> kept_turned; // `turned` was for the faces before coincident ones went
        for (const auto f : kept) kept_turned.push_back(turned[f]);
        imprint_pass(scene, kept_turned, options.contact_gap, report);
    }
    auto mesh = patch_pass(scene, options, report);
    begin_stage(stages, "two-sided, materials, order");
    two_sided_pass(mesh, options, report);
    names_pass(mesh, report);
    specular_pass(mesh, options, report);
    if (const auto problems = material_warnings(mesh, scene.material_sources); !problems.empty()) {
        std::string text = "materials to check before solving:";
        for (const auto& line : problems) text += "\n  " + line;
        report.add(MeshReport::Kind::Warning, text);
    }
    if (options.morton_order) order_patches_by_locality(mesh);
    if (scene_out) *scene_out = std::move(scene);
    return mesh;
}

void check_mesh_memory(std::uint64_t faces, std::uint64_t max_memory, const std::string& source) {
    if (max_memory == 0 || faces * kMeshBytesPerFace <= max_memory) return;
    throw InputError(source + ": its " + std::to_string(faces) +
                     " faces (instances counted) need about " +
                     human_bytes(double(faces * kMeshBytesPerFace)) +
                     " to mesh, more than --max-memory " + human_bytes(double(max_memory)) +
                     " (give a larger --max-memory, or a scene with fewer faces or instances)");
}

} // namespace rad
