// rad-mesh: OBJ reading, subdivision, conformity and bad input.
#include "helpers.hpp"

#include <catch2/catch.hpp>

#include <map>

using namespace testing_helpers;
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

TEST_CASE("bad OBJ input names the file and line") {
    auto error_of = [](const std::string& obj, const std::string& mtl = kGreyMtl) {
        try {
            scene_from_obj(obj, mtl, "bad");
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(error_of("v 0 0 nan\n"),
               Contains("scene.obj:2:") && Contains("not a finite number"));
    CHECK_THAT(error_of("v 0 0 inf\n"), Contains("scene.obj:2:"));
    CHECK_THAT(error_of("v 0 0 0\nusemtl grey\nf 1 2 3\n"),
               Contains("scene.obj:4:") &&
                   Contains("refers to vertex 2, but only 1 vertices are defined"));
    CHECK_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf -4 1 2\n"),
               Contains("scene.obj:6:"));
    CHECK_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
               Contains("scene.obj:5:") && Contains("no material"));
    CHECK_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl chrome\nf 1 2 3\n"),
               Contains("scene.obj:5:") && Contains("unknown material 'chrome'"));
    CHECK_THAT(error_of("# nothing\n"), Contains("empty"));
    CHECK_THAT(error_of("mtllib missing.mtl\n"),
               Contains("scene.obj:2:") && Contains("missing.mtl"));
}

TEST_CASE("non-planar quads are refused, degenerate faces dropped and counted") {
    const auto bent =
        scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0.2\nv 0 1 0\nusemtl grey\nf 1 2 3 4\n");
    REQUIRE_THROWS_WITH(rad::subdivide(bent, {}),
                        Contains("scene.obj:7:") && Contains("not planar"));
    const auto scene =
        scene_from_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\nf 1 2 4\n");
    rad::SubdivisionReport report;
    const auto mesh = rad::subdivide(scene, {}, &report);
    CHECK(report.degenerate_dropped == 1);
    CHECK(mesh.patches.size() == 1);
    const auto all_bad = scene_from_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nusemtl grey\nf 1 2 3\n");
    REQUIRE_THROWS_WITH(rad::subdivide(all_bad, {}), Contains("empty"));
}
