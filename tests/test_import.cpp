// Scenes through assimp: a fixture converted to glTF (and PLY) by assimp's own exporter gives
// the same patches as the OBJ; transforms, emission strength and textures are applied.
#include "helpers.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/vec.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <tuple>

using namespace testing_helpers;
using Catch::Matchers::Contains;

namespace {

// Patches as sorted (centroid, area, reflectance) rows, so two meshes of the same surfaces
// compare whatever order their files listed them in.
std::vector<std::array<double, 7>> rows(const radfmt::MeshData& mesh) {
    std::vector<std::array<double, 7>> out;
    for (const auto& p : mesh.patches) {
        const auto& m = mesh.materials[p.material];
        out.push_back({p.centroid[0], p.centroid[1], p.centroid[2], p.area, m.reflectance[0],
                       m.reflectance[1], m.reflectance[2]});
    }
    std::sort(out.begin(), out.end());
    return out;
}

void convert(const std::filesystem::path& from, const std::filesystem::path& to,
             const char* format) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(from.string(), aiProcess_JoinIdenticalVertices);
    REQUIRE(scene);
    Assimp::Exporter exporter;
    REQUIRE(exporter.Export(scene, format, to.string()) == AI_SUCCESS);
}

} // namespace

TEST_CASE("a fixture converted to glTF by assimp gives the same patches as the OBJ") {
    // McGuire's CornellBox-Sphere: triangles only (glTF holds nothing else).
    const std::filesystem::path obj =
        std::string(RADIOSITY_SOURCE_DIR) + "/tests/data/cornell-sphere/CornellBox-Sphere.obj";
    const auto dir = temp_dir("import");
    for (const char* format : {"gltf2", "glb2"}) {
        CAPTURE(format);
        const auto gltf = dir / (std::string("sphere.") +
                                 (format[1] == 'l' && format[2] == 't' ? "gltf" : "glb"));
        convert(obj, gltf, format);
        rad::SceneReport report;
        const auto from_gltf = rad::load_scene(gltf, {}, &report);
        const auto from_obj = rad::load_scene(obj);
        CHECK(from_gltf.polygons.size() == from_obj.polygons.size());
        for (double edge : {0.0, 0.1}) {
            CAPTURE(edge);
            rad::SubdivisionOptions options;
            options.max_edge = edge;
            const auto a = rows(rad::subdivide(from_obj, options));
            const auto b = rows(rad::subdivide(from_gltf, options));
            REQUIRE(a.size() == b.size());
            double total_a = 0, total_b = 0;
            for (std::size_t i = 0; i < a.size(); ++i) {
                total_a += a[i][3];
                total_b += b[i][3];
            }
            if (edge == 0) {
                // Each OBJ patch has its glTF twin: the nearest centroid (glTF holds floats,
                // so to 1e-6), with the same area and reflectance.
                std::size_t unmatched = 0;
                for (const auto& row : a) {
                    double best = 1e300;
                    const std::array<double, 7>* match = nullptr;
                    for (const auto& other : b) {
                        const double d = std::abs(other[0] - row[0]) + std::abs(other[1] - row[1]) +
                                         std::abs(other[2] - row[2]);
                        if (d < best) best = d, match = &other;
                    }
                    bool same = best < 3e-6;
                    for (int k = 3; k < 7 && same; ++k)
                        same = std::abs((*match)[k] - row[k]) < 1e-6;
                    unmatched += !same;
                }
                CHECK(unmatched == 0);
            }
            CHECK(total_b == Approx(total_a).epsilon(1e-6));
        }
        // The light's Ke survives as emissive colour (assimp writes it unscaled).
        const auto light = std::find_if(from_gltf.materials.begin(), from_gltf.materials.end(),
                                        [](const auto& m) { return m.name == "light"; });
        REQUIRE(light != from_gltf.materials.end());
        CHECK(light->emission[0] > 0);
    }
}

TEST_CASE("glTF: node transforms, mirroring, emissive strength and --emission-scale") {
    // One unit square, used by two nodes: one moved by (10, 0, 0) and scaled by 2, one
    // mirrored in x (its winding must be turned back so that it still faces +z). The
    // material emits (1, 0.5, 0.25) x emissiveStrength 8.
    const auto dir = temp_dir("gltf");
    // Positions of 4 vertices (floats) and 6 indices (u16) in one buffer, base64-free: a file.
    std::vector<float> positions{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<std::uint16_t> indices{0, 1, 2, 0, 2, 3};
    std::string buffer(reinterpret_cast<const char*>(positions.data()), 48);
    buffer.append(reinterpret_cast<const char*>(indices.data()), 12);
    write_text(dir / "square.bin", buffer);
    write_text(dir / "square.gltf", R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_emissive_strength"],
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [
    {"name": "moved", "mesh": 0, "translation": [10, 0, 0], "scale": [2, 2, 2]},
    {"name": "mirrored", "mesh": 0, "scale": [-1, 1, 1]}
  ],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"name": "glow",
                 "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1]},
                 "emissiveFactor": [1, 0.5, 0.25],
                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}],
  "buffers": [{"uri": "square.bin", "byteLength": 60}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ]
})");
    rad::SceneOptions options;
    options.emission_scale = 2;
    const auto scene = rad::load_scene(dir / "square.gltf", options);
    REQUIRE(scene.materials.size() >= 1);
    const auto& glow = scene.materials[0];
    CHECK(glow.name == "glow");
    CHECK(glow.reflectance[0] == Approx(0.5));
    CHECK(glow.reflectance[2] == Approx(0.125));
    CHECK(glow.emission[0] == Approx(1 * 8 * 2));
    CHECK(glow.emission[1] == Approx(0.5 * 8 * 2));
    // The buffer is recorded for the mesh's provenance.
    CHECK(std::count_if(scene.material_files.begin(), scene.material_files.end(),
                        [](const std::string& f) { return f.ends_with("square.bin"); }) == 1);
    const auto mesh = rad::subdivide(scene, {});
    REQUIRE(mesh.patches.size() == 4);
    double moved_area = 0, mirrored_area = 0;
    for (const auto& p : mesh.patches) {
        CHECK(p.normal[2] == Approx(1)); // both still face +z
        const auto& group = mesh.groups[p.group];
        if (group == "moved") {
            moved_area += p.area;
            CHECK(p.centroid[0] > 10);
        } else {
            CHECK(group == "mirrored");
            mirrored_area += p.area;
            CHECK(p.centroid[0] < 0);
        }
    }
    CHECK(moved_area == Approx(4));
    CHECK(mirrored_area == Approx(1));
}

TEST_CASE("unreadable scene files are refused with the file's name") {
    const auto dir = temp_dir("import-bad");
    write_text(dir / "broken.gltf", "{ not json");
    CHECK_THROWS_WITH(rad::load_scene(dir / "broken.gltf"),
                      Contains("broken.gltf") && Contains("cannot read the scene"));
    CHECK_THROWS_WITH(rad::load_scene(dir / "missing.glb"), Contains("missing.glb"));
}

TEST_CASE("PLY and COLLADA conversions of a fixture give the same surfaces") {
    const std::filesystem::path obj =
        std::string(RADIOSITY_SOURCE_DIR) + "/tests/data/cornell-sphere/CornellBox-Sphere.obj";
    const auto dir = temp_dir("import-formats");
    const auto reference = rad::subdivide(rad::load_scene(obj), {});
    for (const auto& [format, name] : {std::pair{"ply", "sphere.ply"}, {"collada", "sphere.dae"}}) {
        CAPTURE(format);
        convert(obj, dir / name, format);
        rad::SceneReport report;
        const auto mesh = rad::subdivide(rad::load_scene(dir / name, {}, &report), {});
        CHECK(mesh.patches.size() == reference.patches.size());
        CHECK(mesh.total_area() == Approx(reference.total_area()).epsilon(1e-6));
    }
}

namespace {
// COLLADA nodes nested `depth` deep around one triangle: importers recurse once a level.
std::string nested_collada(int depth) {
    std::string nodes;
    for (int i = 0; i < depth; ++i) nodes += "<node id=\"n" + std::to_string(i) + "\">";
    nodes += "<instance_geometry url=\"#g\"/>";
    for (int i = 0; i < depth; ++i) nodes += "</node>";
    return R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><up_axis>Y_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
<technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>
<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s">)" +
           nodes + R"(</visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>)";
}
} // namespace

TEST_CASE("an importer that crashes takes its own process, not the tool's") {
    const auto dir = temp_dir("isolated");
    write_text(dir / "deep.dae", nested_collada(20000));
    rad::SceneOptions options;
    // A stack too small for 20000 levels: assimp overflows it and dies of SIGSEGV, in the
    // child; the tool gets an error naming the file and the signal.
    options.import.stack_bytes = 256 * 1024;
    CHECK_THROWS_WITH(rad::load_scene(dir / "deep.dae", options),
                      Contains("deep.dae: the importer (assimp) failed on this file (signal 11 "
                               "(SIGSEGV): it crashed") &&
                          Contains("nothing was written"));
    // With the default stack (512 MiB) the same file reads.
    const auto scene = rad::load_scene(dir / "deep.dae");
    CHECK(scene.polygons.size() == 1);
    CHECK(scene.groups.size() == 1);
}

TEST_CASE("an isolated import gives the scene and report an import in the tool's process does") {
    const auto path = fs::path(RADIOSITY_SOURCE_DIR) / "tests/data/living-room/living_room.glb";
    rad::SceneOptions in_process;
    in_process.import.isolate = false;
    rad::SceneReport report_isolated, report_here;
    const auto isolated = rad::load_scene(path, {}, &report_isolated);
    const auto here = rad::load_scene(path, in_process, &report_here);
    REQUIRE(here.polygons.size() > 1000);
    CHECK(isolated.vertices == here.vertices);
    CHECK(isolated.polygons.size() == here.polygons.size());
    bool same = true;
    for (std::size_t i = 0; i < here.polygons.size() && same; ++i) {
        const auto &a = isolated.polygons[i], &b = here.polygons[i];
        same = a.vertices == b.vertices && a.group == b.group && a.material == b.material &&
               a.line == b.line && a.vn_sum == b.vn_sum;
    }
    CHECK(same);
    CHECK(isolated.groups == here.groups);
    CHECK(isolated.material_files == here.material_files);
    CHECK(isolated.face_ranges.size() == here.face_ranges.size());
    CHECK(report_isolated.textures_averaged == report_here.textures_averaged);
    CHECK(report_isolated.texture_problems == report_here.texture_problems);
}
