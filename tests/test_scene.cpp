// rad-mesh: OBJ reading, subdivision, conformity and bad input.
#include "helpers.hpp"
#include "radiosity/image_io.hpp"
#include "radiosity/random.hpp"
#include "radiosity/vec.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

using namespace testing_helpers;
using rad::operator-;
using Catch::Matchers::Contains;

TEST_CASE("materials come from the MTL, Ke included, and groups are kept") {
    const auto scene =
        scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng panel\nusemtl lamp\nf 1 2 3 4\n");
    REQUIRE(scene.materials.size() == 2);
    const auto& lamp = scene.materials[scene.polygons[0].material];
    CHECK(lamp.name == "lamp");
    CHECK(lamp.reflectance == radfmt::Rgb{0.2, 0.2, 0.2});
    CHECK(lamp.emission == radfmt::Rgb{10, 8, 6});
    CHECK(scene.groups[scene.polygons[0].group] == "panel");
    CHECK(scene.polygons[0].line == 8); // after the helper's mtllib line
}

TEST_CASE("negative (relative) indices work") {
    const auto scene = scene_from_obj("usemtl grey\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
    REQUIRE(scene.polygons.size() == 1);
    CHECK(scene.polygons[0].vertices == std::vector<std::uint32_t>{0, 1, 2});
}

TEST_CASE("subdivision preserves area and gives the expected patch counts") {
    // A 2 x 1 quad and a right triangle with legs 1.
    const std::string obj = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\n"
                            "usemtl grey\ng quad\nf 1 2 3 4\ng tri\nf 5 6 7\n";
    for (double edge : {0.0, 0.5, 0.3, 0.1, 0.07}) {
        const auto mesh = mesh_from_obj(obj, edge);
        CAPTURE(edge);
        CHECK(std::abs(mesh.total_area() - 2.5) < 1e-9 * 2.5);
        std::size_t quads = 0, tris = 0;
        for (const auto& p : mesh.patches) (p.corner_count() == 4 ? quads : tris)++;
        if (edge == 0.5) {
            CHECK(quads == 4 * 2); // 4 x 2 grid
            CHECK(tris == 3 * 3);  // legs need 2 segments, the hypotenuse 3: all take 3
        }
        for (const auto& p : mesh.patches) {
            for (int a = 0; a < p.corner_count(); ++a) {
                const auto& u = mesh.vertices[p.corners[a]];
                const auto& v = mesh.vertices[p.corners[(a + 1) % p.corner_count()]];
                const double len =
                    std::sqrt((u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) +
                              (u[2] - v[2]) * (u[2] - v[2]));
                if (edge > 0) CHECK(len <= edge * (1 + 1e-9));
            }
        }
    }
}

TEST_CASE("area limits and per-group overrides") {
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "usemtl grey\ng floor\nf 1 2 3 4\ng roof\nf 5 8 7 6\n";
    rad::SubdivisionOptions options;
    options.max_area = 0.1;
    options.max_edge_by_group["floor"] = 0.25;
    const auto mesh = rad::subdivide(scene_from_obj(obj), options);
    std::map<std::uint32_t, int> per_group;
    for (const auto& p : mesh.patches) {
        ++per_group[p.group];
        CHECK(p.area <= 0.1 + 1e-12);
    }
    CHECK(per_group[0] == 16); // floor: 4 x 4
    CHECK(per_group[1] == 12); // roof: the grid grows 1x1 -> 2x2 -> 3x3 -> 4x3 until 1/12 <= 0.1
    CHECK(std::abs(mesh.total_area() - 2) < 1e-9);
}

TEST_CASE("a subdivided closed cube is conforming: every edge has exactly two patches") {
    for (double edge : {1.0, 0.5, 0.3, 0.2}) {
        const auto mesh = mesh_from_obj(cube_obj(), edge);
        const auto topo = rad::analyze_topology(mesh);
        CAPTURE(edge);
        CHECK(topo.rejected_patches == 0);
        CHECK(topo.boundary_edges == 0);
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const auto& p : mesh.patches)
            for (int k = 0; k < p.corner_count(); ++k) {
                auto a = p.corners[k], b = p.corners[(k + 1) % p.corner_count()];
                ++uses[{std::min(a, b), std::max(a, b)}];
            }
        for (const auto& [e, n] : uses) CHECK(n == 2);
        CHECK(std::abs(mesh.total_area() - 6) < 6e-9);
        // Euler characteristic of a sphere: V - E + F = 2.
        CHECK(long(mesh.vertices.size()) - long(uses.size()) + long(mesh.patches.size()) == 2);
    }
}

TEST_CASE("polygons with more than four vertices and concave quads are triangulated") {
    // An L-shaped hexagon, area 3.
    const auto mesh = mesh_from_obj(
        "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nusemtl grey\nf 1 2 3 4 5 6\n"
        "v 5 0 0\nv 7 0 0\nv 6 0.2 0\nv 6 2 0\nf 7 8 9 10\n",
        0.4);
    double total = 0;
    for (const auto& p : mesh.patches) {
        CHECK(p.corner_count() == 3);
        CHECK(p.normal[2] == Approx(1));
        total += p.area;
    }
    CHECK(total == Approx(3 + 1.1).epsilon(1e-12)); // hexagon 3, concave quad 1.1 (shoelace)
}

// OBJ text: a polygon of `n` corners at radius r (alternating with r_odd when given) in the
// plane z = 0, counter-clockwise, then a triangle after it.
std::string polygon_then_triangle(int n, double r, double r_odd) {
    std::string obj;
    char line[128];
    for (int k = 0; k < n; ++k) {
        const double a = 2 * 3.141592653589793 * k / n, radius = k % 2 ? r_odd : r;
        std::snprintf(line, sizeof line, "v %.9f %.9f 0\n", radius * std::cos(a),
                      radius * std::sin(a));
        obj += line;
    }
    obj += "usemtl grey\nf";
    for (int k = 1; k <= n; ++k) {
        std::snprintf(line, sizeof line, " %d", k);
        obj += line;
    }
    std::snprintf(line, sizeof line, "\nv 20 0 0\nv 22 0 0\nv 20 2 0\nf %d %d %d\n", n + 1, n + 2,
                  n + 3);
    obj += line;
    return obj;
}

// The shoelace area of the first `n` vertices of a mesh's scene.
double shoelace(const std::vector<rad::Vec3>& v, int n) {
    double twice = 0;
    for (int k = 0; k < n; ++k) twice += v[k][0] * v[(k + 1) % n][1] - v[(k + 1) % n][0] * v[k][1];
    return twice / 2;
}

TEST_CASE("faces of hundreds of corners are read whole and triangulated") {
    // tinyobjloader keeps a face's corner count in a byte: a face of 300 corners read as 44,
    // and the triangle after it began inside it. A star of 1,000 corners is past what ear
    // clipping does quickly (constrained Delaunay).
    for (const auto& [n, r_odd] : {std::pair{300, 5.0}, std::pair{1000, 3.0}}) {
        const auto obj = polygon_then_triangle(n, 5, r_odd);
        const auto scene = scene_from_obj(obj);
        REQUIRE(scene.polygons.size() == 2);
        CHECK(scene.polygons[0].vertices.size() == std::size_t(n));
        CHECK(scene.polygons[1].vertices == std::vector<std::uint32_t>{std::uint32_t(n),
                                                                       std::uint32_t(n + 1),
                                                                       std::uint32_t(n + 2)});
        const double polygon = shoelace(scene.vertices, n);
        const auto mesh = mesh_from_obj(obj);
        double total = 0;
        for (const auto& p : mesh.patches) {
            CHECK(p.normal[2] == Approx(1));
            total += p.area;
        }
        CHECK(total == Approx(polygon + 2).epsilon(1e-9));
        CHECK(mesh.patches.size() == std::size_t(n - 2 + 1));
    }
}

namespace {
// Loads `obj` (with `mtl` as scene.mtl beside it) with `options`; returns the error or
// "no error", and the scene and report when it loads.
std::string load_with(const std::string& obj, const rad::SceneOptions& options,
                      rad::Scene* scene = nullptr, rad::SceneReport* report = nullptr,
                      const std::string& mtl = kGreyMtl) {
    const auto dir = temp_dir("load");
    write_text(dir / "scene.mtl", mtl);
    write_text(dir / "scene.obj", "mtllib scene.mtl\n" + obj);
    try {
        auto loaded = rad::load_obj(dir / "scene.obj", options, report);
        if (scene) *scene = std::move(loaded);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "no error";
}
rad::SceneOptions strict_options() {
    rad::SceneOptions options;
    options.strict = true;
    return options;
}
} // namespace

TEST_CASE("bad OBJ input names the file and line") {
    auto error_of = [](const std::string& obj) { return load_with(obj, {}); };
    CHECK_THAT(error_of("v 0 0 nan\n"),
               Contains("scene.obj:2:") && Contains("not a finite number"));
    CHECK_THAT(error_of("v 0 0 inf\n"), Contains("scene.obj:2:"));
    CHECK_THAT(error_of("v 0 0 0\nusemtl grey\nf 1 2 3\n"),
               Contains("scene.obj:4:") &&
                   Contains("refers to vertex 2, but only 1 vertices are defined"));
    CHECK_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf -4 1 2\n"),
               Contains("scene.obj:6:"));
    CHECK_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 0 1 2\n"),
               Contains("scene.obj:6:") && Contains("refers to vertex 0"));
    CHECK_THAT(error_of("# nothing\n"), Contains("empty"));
    // One number grammar with tinyobjloader: what it would read as something else is refused.
    CHECK_THAT(error_of("v 0x2 2 0\n"), Contains("scene.obj:2:") && Contains("'0x2'"));
    CHECK_THAT(error_of("v 1e400 2 0\n"), Contains("scene.obj:2:") && Contains("double range"));
    CHECK_THAT(error_of("v 1 2 0 junk\n"), Contains("scene.obj:2:") && Contains("'junk'"));
    CHECK_THAT(error_of("v 1 2 0 1 1 1 1\n"), Contains("scene.obj:2:"));
    // A weight, an r g b colour and a trailing comment are fine.
    const std::string face = "usemtl grey\nf 1 2 3\n";
    CHECK(error_of("v 0 0 0 1\nv 1 0 0\nv 0 1 0\n" + face) == "no error");
    CHECK(error_of("v 0 0 0 0.5 0.2 0.1\nv 1 0 0 # x\nv 0 1 0\n" + face) == "no error");
}

TEST_CASE("faces without a known material get the default one; --strict refuses them") {
    const std::string no_usemtl = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl grey\nf 1 3 2\n";
    rad::Scene scene;
    rad::SceneReport report;
    CHECK(load_with(no_usemtl, {}, &scene, &report) == "no error");
    CHECK(report.faces_defaulted == 1);
    CHECK(report.first_defaulted_line == 5);
    CHECK(report.default_material == "default");
    REQUIRE(scene.polygons.size() == 2);
    const auto& fallback = scene.materials[scene.polygons[0].material];
    CHECK(fallback.name == "default");
    CHECK(fallback.reflectance == radfmt::Rgb{{0.5, 0.5, 0.5}});
    CHECK(scene.materials[scene.polygons[1].material].name == "grey");
    CHECK_THAT(load_with(no_usemtl, strict_options()),
               Contains("scene.obj:5:") && Contains("no material"));

    // A name no library defines: the same default, and the name reported with its line.
    const std::string chrome = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl chrome\nf 1 2 3\n";
    rad::SceneOptions options;
    options.default_reflectance = {{0.2, 0.3, 0.4}};
    rad::SceneReport chrome_report;
    CHECK(load_with(chrome, options, &scene, &chrome_report) == "no error");
    CHECK(chrome_report.unknown_materials == std::vector<std::string>{"chrome (line 5)"});
    CHECK(scene.materials[scene.polygons[0].material].reflectance == radfmt::Rgb{{0.2, 0.3, 0.4}});
    CHECK_THAT(load_with(chrome, strict_options()),
               Contains("scene.obj:5:") && Contains("unknown material 'chrome'"));
    // A scene that has a material called "default" keeps it; the fallback is another.
    rad::SceneReport taken;
    CHECK(load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", {}, &scene, &taken,
                    "newmtl default\nKd 0.9 0.1 0.1\n") == "no error");
    CHECK(taken.default_material == "default_");
}

TEST_CASE("material libraries as found: missing, elsewhere, several per line, odd whitespace") {
    // Missing: reported with where it was looked for; --strict refuses.
    rad::Scene scene;
    rad::SceneReport report;
    const std::string obj = "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n";
    CHECK(load_with(obj, {}, &scene, &report) == "no error");
    REQUIRE(report.missing_libraries.size() == 1);
    CHECK_THAT(report.missing_libraries[0],
               Contains("'missing.mtl' (line 2) not found; looked for") &&
                   Contains("missing.mtl, "));
    CHECK_THAT(load_with(obj, strict_options()),
               Contains("scene.obj:2:") && Contains("material library 'missing.mtl' not found"));

    // In another folder given with mtl_paths; two libraries on one line, one with an escaped
    // space in its name; newmtl with repeated and trailing whitespace; usemtl likewise.
    const auto dir = temp_dir("libraries");
    std::filesystem::create_directories(dir / "materials");
    write_text(dir / "materials" / "a b.mtl", "newmtl   red  \nKd 0.8 0.1 0.1\n");
    write_text(dir / "materials" / "second.mtl", "newmtl blue\t\nKd 0.1 0.1 0.8\r\n");
    write_text(dir / "scene.obj", "mtllib a\\ b.mtl   second.mtl  \nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                  "usemtl   red   \nf 1 2 3\nusemtl blue\r\nf 1 3 2\n");
    rad::SceneOptions options;
    REQUIRE_THROWS_WITH(rad::load_obj(dir / "scene.obj", strict_options()),
                        Contains("material library 'a b.mtl' not found") && Contains("--mtl-path"));
    options.mtl_paths = {dir / "materials"};
    rad::SceneReport found;
    const auto loaded = rad::load_obj(dir / "scene.obj", options, &found);
    CHECK(found.missing_libraries.empty());
    CHECK(found.unknown_materials.empty());
    CHECK(found.faces_defaulted == 0);
    REQUIRE(loaded.polygons.size() == 2);
    CHECK(loaded.materials[loaded.polygons[0].material].name == "red");
    CHECK(loaded.materials[loaded.polygons[0].material].reflectance[0] == Approx(0.8));
    CHECK(loaded.materials[loaded.polygons[1].material].name == "blue");
    CHECK(loaded.material_files.size() == 2);
}

TEST_CASE(
    "non-planar faces are split into triangles (refused with strict); degenerate faces dropped") {
    const auto bent =
        scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0.2\nv 0 1 0\nusemtl grey\nf 1 2 3 4\n");
    rad::SubdivisionReport split;
    const auto mesh_bent = rad::subdivide(bent, {}, &split);
    CHECK(split.nonplanar_split == 1);
    CHECK(split.worst_nonplanar_line == 7);
    CHECK(split.worst_nonplanar_offset > 0.04);
    CHECK(split.worst_nonplanar_offset < 0.2);
    REQUIRE(mesh_bent.patches.size() == 2);
    // Each triangle has its own plane. The diagonal chosen is the one whose two triangles
    // fold least: 2-4 (normals (-0.2,-0.2,1) and (0,0,1), cosine 0.962) rather than 1-3
    // ((0,-0.2,1) and (-0.2,0,1), cosine 0.9615).
    double area = 0;
    for (const auto& p : mesh_bent.patches) {
        CHECK(p.corner_count() == 3);
        CHECK(rad::length(p.normal) == Approx(1));
        area += p.area;
    }
    CHECK(area == Approx(0.5 * std::sqrt(1.08) + 0.5).epsilon(1e-12));
    rad::SubdivisionOptions strict;
    strict.strict = true;
    REQUIRE_THROWS_WITH(rad::subdivide(bent, strict), Contains("scene.obj:7:") &&
                                                          Contains("not planar") &&
                                                          Contains("without --strict it is split"));
    // Within the tolerance (relative to the face's size) a face stays one quad.
    const auto slight =
        scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0.0005\nv 0 1 0\nusemtl grey\nf 1 2 3 4\n");
    rad::SubdivisionReport none;
    CHECK(rad::subdivide(slight, {}, &none).patches.size() == 1);
    CHECK(none.nonplanar_split == 0);

    const auto scene =
        scene_from_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\nf 1 2 4\n");
    rad::SubdivisionReport report;
    const auto mesh = rad::subdivide(scene, {}, &report);
    CHECK(report.degenerate_dropped == 1);
    CHECK(mesh.patches.size() == 1);
    const auto all_bad = scene_from_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nusemtl grey\nf 1 2 3\n");
    REQUIRE_THROWS_WITH(rad::subdivide(all_bad, {}), Contains("empty"));
}

TEST_CASE("map_Kd textures: their mean linear colour multiplies Kd, or replaces a Kd of 0") {
    const auto dir = temp_dir("textures");
    // A 4 x 2 texture, left half linear 0.2, right half 0.6 (written as 8-bit sRGB): the mean
    // is 0.4 in linear light; averaging the encoded values would give 0.37.
    rad::Image image;
    image.width = 4;
    image.height = 2;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) image.rgb.push_back(x < 2 ? 0.2f : 0.6f);
    std::filesystem::create_directories(dir / "maps");
    rad::write_png((dir / "maps" / "wood.png").string(), image, 1.0);
    write_text(dir / "scene.mtl", "newmtl tinted\nKd 0.5 1 0.5\nmap_Kd maps/wood.png\n"
                                  "newmtl black\nKd 0 0 0\nmap_Kd maps/wood.png\n"
                                  "newmtl nokd\nmap_Kd maps/wood.png\n"
                                  "newmtl lost\nKd 0.3 0.3 0.3\nmap_Kd maps/none.png\n");
    std::string obj = "mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const char* m : {"tinted", "black", "nokd", "lost"}) {
        obj += "usemtl ";
        obj += m;
        obj += "\nf 1 2 3\n";
    }
    write_text(dir / "scene.obj", obj);
    rad::SceneReport report;
    const auto scene = rad::load_obj(dir / "scene.obj", {}, &report);
    auto reflectance = [&](const std::string& name) {
        for (const auto& m : scene.materials)
            if (m.name == name) return m.reflectance;
        FAIL("no material " << name);
        return radfmt::Rgb{};
    };
    const double mean = 0.4, quantum = 0.004; // 8-bit rounding in sRGB
    CHECK(reflectance("tinted")[0] == Approx(0.5 * mean).margin(quantum));
    CHECK(reflectance("tinted")[1] == Approx(1.0 * mean).margin(quantum));
    CHECK(reflectance("black")[2] == Approx(mean).margin(quantum));
    CHECK(reflectance("nokd")[0] == Approx(mean).margin(quantum));
    CHECK(reflectance("lost")[0] == Approx(0.3)); // keeps its Kd
    CHECK(report.textures_averaged.size() == 3);
    CHECK(report.textures_replacing_kd == std::vector<std::string>{"black", "nokd"});
    REQUIRE(report.texture_problems.size() == 1);
    CHECK_THAT(report.texture_problems[0], Contains("lost") && Contains("none.png not found"));
    // The texture is recorded with the MTL for provenance.
    CHECK(std::count_if(scene.material_files.begin(), scene.material_files.end(),
                        [](const std::string& f) { return f.ends_with("wood.png"); }) == 1);

    // An unreadable texture (not an image) is named with stb_image's reason.
    write_text(dir / "maps" / "none.png", "not a png");
    rad::SceneReport broken;
    rad::load_obj(dir / "scene.obj", {}, &broken);
    REQUIRE(broken.texture_problems.size() == 1);
    CHECK_THAT(broken.texture_problems[0], Contains("unreadable"));
}

namespace {
// Longest edge squared over twice the area: 1.15 for an equilateral triangle, 1 for a
// square; a patch of aspect ratio k has about k.
double patch_elongation(const radfmt::MeshData& mesh, const radfmt::Patch& p) {
    double longest = 0;
    for (int k = 0; k < p.corner_count(); ++k) {
        const auto d =
            mesh.vertices[p.corners[(k + 1) % p.corner_count()]] - mesh.vertices[p.corners[k]];
        longest = std::max(longest, rad::dot(d, d));
    }
    return longest / (2 * p.area);
}
} // namespace

TEST_CASE("long thin triangles: patches grow with area and perimeter, conforming, not too thin") {
    // The tunnel case: a 466 x 0.13 strip written as two triangles, at --max-edge 10. The
    // regular n x n pattern gave 2 x 47^2 = 4418 patches.
    auto strip = [](double length, double width) {
        std::string obj;
        obj += "v 0 0 0\nv " + std::to_string(length) + " 0 0\nv " + std::to_string(length) + " " +
               std::to_string(width) + " 0\nv 0 " + std::to_string(width) + " 0\n";
        obj += "usemtl grey\nf 1 2 3\nf 1 3 4\n";
        return scene_from_obj(obj);
    };
    for (const auto& [length, width, edge] : {std::tuple{466.0, 0.13, 10.0},
                                              {466.0, 0.13, 1.0},
                                              {100.0, 10.0, 1.0},
                                              {50.0, 5.0, 0.5}}) {
        CAPTURE(length, width, edge);
        rad::SubdivisionOptions options;
        options.max_edge = edge;
        const auto mesh = rad::subdivide(strip(length, width), options);
        const double area = length * width, perimeter = 2 * (length + width);
        // About one patch per half square of the edge, plus one or two per segment of the
        // outline (the triangles' shared diagonal is outline to both): linear, not like
        // (longest edge / max-edge)^2.
        const double expected = area / (0.5 * edge * edge) + perimeter / edge;
        CAPTURE(mesh.patches.size(), expected);
        CHECK(double(mesh.patches.size()) <= 2.2 * expected);
        CHECK(double(mesh.patches.size()) >= 0.5 * expected);
        double total = 0;
        std::vector<double> elongations;
        for (const auto& p : mesh.patches) {
            total += p.area;
            CHECK(p.normal[2] == Approx(1));
            // No patch edge much longer than the limit: rows and bands are about `edge`
            // apart, and a zipper diagonal spans one band and a little along it.
            for (int k = 0; k < 3; ++k)
                CHECK(rad::length(mesh.vertices[p.corners[(k + 1) % 3]] -
                                  mesh.vertices[p.corners[k]]) <= edge * 2.5);
            if (width >= edge) elongations.push_back(patch_elongation(mesh, p));
        }
        CHECK(total == Approx(area).epsilon(1e-9));
        // Conforming: the only open edges are the outline's segments, and every patch is
        // accepted by OpenMesh (no T-vertices, no overlaps).
        const auto topology = rad::analyze_topology(mesh);
        CHECK(topology.rejected_patches == 0);
        CHECK(topology.boundary_edges ==
              2 * static_cast<std::size_t>(std::ceil(length / edge - 1e-9)) +
                  2 * static_cast<std::size_t>(std::ceil(width / edge - 1e-9)));
        // Where the strip is wide enough for it, patches are not slivers: 95% have an
        // elongation below 4 (a right isosceles triangle has 2), and none is worse than the
        // face's own triangles (10.1: the regular n x n pattern copies that shape into every
        // patch); the worst sit in the 5.7 degree corners, which no patch can widen.
        if (!elongations.empty()) {
            std::sort(elongations.begin(), elongations.end());
            CHECK(elongations[elongations.size() * 95 / 100] < 4);
            CHECK(elongations.back() < 1.5 * (length * length + width * width) / (length * width));
        }
    }
}

TEST_CASE("mixed slivers and regular triangles with different limits stay conforming") {
    // A strip between two wavy lines, triangulated into triangles of every shape (slivers
    // next to fat ones), in two groups with different --max-edge: conforming means every
    // patch has area, the areas add up, and the only edges used by one patch are the
    // outline's (a T-vertex would leave an inner edge with one patch and lengthen it).
    std::string obj;
    const int n = 40;
    rad::Rng rng(7, 0);
    std::vector<rad::Vec3> bottom, top;
    double x = 0;
    for (int k = 0; k <= n; ++k) {
        bottom.push_back({x, 0.3 * std::sin(0.7 * k), 0});
        top.push_back({x + 3 * rng.uniform(), 2 + 0.5 * std::cos(1.3 * k) + rng.uniform(), 0});
        x += 0.2 + 4 * rng.uniform() * rng.uniform();
    }
    for (const auto& v : bottom)
        obj += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " 0\n";
    for (const auto& v : top)
        obj += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " 0\n";
    obj += "usemtl grey\n";
    for (int k = 0; k < n; ++k) {
        const int b0 = k + 1, b1 = k + 2, t0 = n + 2 + k, t1 = n + 3 + k;
        obj += k % 2 ? "g left\n" : "g right\n";
        obj += "f " + std::to_string(b0) + " " + std::to_string(b1) + " " + std::to_string(t1) +
               "\nf " + std::to_string(b0) + " " + std::to_string(t1) + " " + std::to_string(t0) +
               "\n";
    }
    const auto scene = scene_from_obj(obj);
    double area = 0;
    for (const auto& p : scene.polygons) {
        std::vector<rad::Vec3> pts;
        for (auto v : p.vertices) pts.push_back(scene.vertices[v]);
        area += 0.5 * rad::length(rad::newell_normal(pts));
    }
    // Large limits leave most edges whole (one segment) while a neighbour splits a side;
    // no limit at all must give back the input triangles.
    for (const auto& [edge, left] :
         {std::pair{0.5, 0.5}, {0.3, 1.1}, {2.0, 0.25}, {100.0, 100.0}, {100.0, 0.5}, {0.0, 0.0}}) {
        CAPTURE(edge, left);
        rad::SubdivisionOptions options;
        options.max_edge = edge;
        options.max_edge_by_group["left"] = left;
        const auto mesh = rad::subdivide(scene, options);
        double total = 0;
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const auto& p : mesh.patches) {
            CHECK(p.area > 1e-9);
            total += p.area;
            for (int k = 0; k < p.corner_count(); ++k) {
                auto a = p.corners[k], b = p.corners[(k + 1) % p.corner_count()];
                ++uses[{std::min(a, b), std::max(a, b)}];
            }
        }
        CHECK(total == Approx(area).epsilon(1e-9));
        double open_length = 0;
        for (const auto& [e, count] : uses) {
            CHECK(count <= 2);
            if (count == 1)
                open_length += rad::length(mesh.vertices[e.first] - mesh.vertices[e.second]);
        }
        // The outline as read (the OBJ holds 6 decimals).
        const auto& v = scene.vertices;
        double outline = rad::length(v[n + 1] - v[0]) + rad::length(v[2 * n + 1] - v[n]);
        for (int k = 0; k < n; ++k)
            outline += rad::length(v[k + 1] - v[k]) + rad::length(v[n + 2 + k] - v[n + 1 + k]);
        CHECK(open_length == Approx(outline).epsilon(1e-9));
        CHECK(rad::analyze_topology(mesh).rejected_patches == 0);
        if (edge == 0) CHECK(mesh.patches.size() == scene.polygons.size());
    }
}

TEST_CASE("MTL colours: refused with file:line when not numbers, one value means grey") {
    auto error_of = [](const std::string& mtl) {
        return load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n", {}, nullptr, nullptr,
                         mtl);
    };
    CHECK_THAT(error_of("newmtl grey\nKd abc 0.5 0.5\n"),
               Contains("scene.mtl:2:") && Contains("Kd value 'abc' is not a finite"));
    CHECK_THAT(error_of("newmtl grey\nKd nan nan nan\n"), Contains("scene.mtl:2:"));
    CHECK_THAT(error_of("newmtl grey\nKd 0.5 0.5 0.5\nKe inf 1 1\n"),
               Contains("scene.mtl:3:") && Contains("Ke value 'inf'"));
    CHECK_THAT(error_of("newmtl grey\nKe ten\n"), Contains("scene.mtl:2:"));
    CHECK_THAT(error_of("newmtl grey\nKd 0.5 0.5\n"), Contains("needs 1 value (grey) or 3"));
    CHECK_THAT(error_of("newmtl grey\nKd -0.5 0.5 0.5\n"), Contains("is negative"));
    rad::Scene scene;
    CHECK(load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n", {}, &scene, nullptr,
                    "newmtl grey\nKd 0.9\nKa 0.1 0.2 0.3 # a comment\n") == "no error");
    CHECK(scene.materials[0].reflectance == radfmt::Rgb{{0.9, 0.9, 0.9}});
}

TEST_CASE("an OBJ starting with a UTF-8 byte-order mark keeps its first vertex") {
    const auto dir = temp_dir("bom");
    write_text(dir / "scene.mtl", kGreyMtl);
    write_text(dir / "scene.obj", "\xEF\xBB\xBFv 0 0 0\nv 2 0 0\nv 0 2 0\nv 9 9 9\nmtllib "
                                  "scene.mtl\nusemtl grey\nf 1 2 3\n");
    const auto scene = rad::load_obj(dir / "scene.obj");
    REQUIRE(scene.vertices.size() == 4);
    REQUIRE(scene.polygons.size() == 1);
    const auto mesh = rad::subdivide(scene, {});
    CHECK(mesh.total_area() == Approx(2)); // vertices 1 2 3, not 2 3 4
}

TEST_CASE("patches are numbered along a Morton curve, each patch unchanged") {
    // A room of six walls, cut fine: the faces' own order runs wall by wall.
    const std::string obj =
        "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 3\nv 2 0 3\nv 2 1 3\nv 0 1 3\n"
        "usemtl grey\nf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n";
    rad::SubdivisionOptions options;
    options.max_edge = 0.1;
    const auto before = rad::subdivide(scene_from_obj(obj), options);
    auto after = before;
    rad::order_patches_by_locality(after);
    REQUIRE(after.patches.size() == before.patches.size());
    CHECK(after.vertices.size() == before.vertices.size());
    // The same patches (corner points, group, area), each once.
    auto points_of = [](const radfmt::MeshData& m, const radfmt::Patch& p) {
        std::vector<radfmt::Vec3> points;
        for (int k = 0; k < p.corner_count(); ++k) points.push_back(m.vertices[p.corners[k]]);
        return points;
    };
    std::map<std::vector<radfmt::Vec3>, double> area_of;
    for (const auto& p : before.patches) area_of[points_of(before, p)] = p.area;
    REQUIRE(area_of.size() == before.patches.size());
    for (const auto& p : after.patches) {
        const auto it = area_of.find(points_of(after, p));
        REQUIRE(it != area_of.end());
        CHECK(it->second == p.area);
        area_of.erase(it);
    }
    // Morton codes of the centroids never decrease, and the order is not the faces' order.
    rad::Box box;
    for (const auto& p : after.patches) box.add(p.centroid);
    // The centroids' bounding cube: its side is their longest extent.
    const double side =
        std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
    const double cell = side / double(rad::kMortonSteps);
    std::uint64_t previous = 0, descents_before = 0;
    for (const auto& p : after.patches) {
        const auto code = rad::morton_code(p.centroid, box.lo, cell);
        CHECK(code >= previous);
        previous = code;
    }
    previous = 0;
    for (const auto& p : before.patches) {
        const auto code = rad::morton_code(p.centroid, box.lo, cell);
        descents_before += code < previous;
        previous = code;
    }
    CHECK(descents_before > 0);
    // Vertices are numbered in order of first use.
    std::uint32_t next = 0;
    for (const auto& p : after.patches)
        for (int k = 0; k < p.corner_count(); ++k) {
            CHECK(p.corners[k] <= next);
            if (p.corners[k] == next) ++next;
        }
    // Neighbours in memory are neighbours in space: consecutive patches are close.
    auto mean_step = [](const radfmt::MeshData& m) {
        double sum = 0;
        for (std::size_t i = 1; i < m.patches.size(); ++i)
            sum += rad::length(m.patches[i].centroid - m.patches[i - 1].centroid);
        return sum / double(m.patches.size() - 1);
    };
    CHECK(mean_step(after) < 0.2);
    // Quantised codes: the spread bits land on every third bit.
    CHECK(rad::morton_code({1, 0, 0}, {0, 0, 0}, 1) == 1);
    CHECK(rad::morton_code({0, 1, 0}, {0, 0, 0}, 1) == 2);
    CHECK(rad::morton_code({0, 0, 1}, {0, 0, 0}, 1) == 4);
    CHECK(rad::morton_code({3, 0, 0}, {0, 0, 0}, 1) == 9);
}

TEST_CASE("a texture is decoded once per run, and one over the pixel limit not at all") {
    const auto dir = temp_dir("texture-cache");
    rad::Image image;
    image.width = image.height = 16;
    image.rgb.assign(16 * 16 * 3, 0.5f);
    rad::write_png((dir / "shared.png").string(), image, 1.0);
    // 40 materials on one texture (a game map's walls): one decode, 40 means.
    std::string mtl, obj = "mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int m = 0; m < 40; ++m) {
        mtl += "newmtl m" + std::to_string(m) + "\nKd 1 1 1\nmap_Kd shared.png\n";
        obj += "usemtl m" + std::to_string(m) + "\nf 1 2 3\n";
    }
    write_text(dir / "scene.mtl", mtl);
    write_text(dir / "scene.obj", obj);
    const auto before = rad::texture_decodes();
    rad::SceneReport report;
    const auto scene = rad::load_obj(dir / "scene.obj", {}, &report);
    CHECK(rad::texture_decodes() - before == 1);
    CHECK(report.textures_averaged.size() == 40);
    for (const auto& m : scene.materials) CHECK(m.reflectance[0] == Approx(0.5).epsilon(0.02));
    // Over the limit: refused from its header (16 x 16 = 256 pixels > 100), never decoded;
    // the materials keep their Kd, with the reason.
    rad::SceneOptions options;
    options.max_texture_pixels = 100;
    rad::SceneReport limited;
    const auto kept = rad::load_obj(dir / "scene.obj", options, &limited);
    CHECK(rad::texture_decodes() - before == 1);
    REQUIRE(limited.texture_problems.size() == 40);
    CHECK_THAT(limited.texture_problems[0],
               Catch::Matchers::Contains("16 x 16 pixels, over the limit of 100 "
                                         "(--max-texture-pixels raises it)"));
    CHECK(kept.materials[0].reflectance[0] == 1);
}
