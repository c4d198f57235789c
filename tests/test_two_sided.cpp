// Two-sided surfaces: back patches are real surfaces (symmetry), rays meet the side that
// faces them, and the selection names groups, materials or all.
#include "helpers.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/solver.hpp"
#include "radiosity/twins.hpp"
#include "radiosity/two_sided.hpp"
#include "radiosity/vec.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace testing_helpers;
using rad::operator-;

namespace {

const std::string kMaterials = "newmtl grey\nKd 0.5 0.5 0.5\n"
                               "newmtl paper\nKd 0.6 0.6 0.6\n"
                               "newmtl lamp\nKd 0 0 0\nKe 10 10 10\n";

// A 2 m room (faces inward) with a lamp on the ceiling facing down and a 1 m sheet of paper
// across the middle at y = 1 facing up. `mirrored`: the room and lamp mirrored to y -> 2 - y
// (the lamp now on the floor, facing up), the sheet unchanged: light reaches its back.
std::string room_with_sheet(bool mirrored) {
    std::string obj = "mtllib scene.mtl\n";
    int count = 0;
    auto face = [&](std::vector<rad::Vec3> corners, const std::string& group,
                    const std::string& material, bool mirror) {
        if (mirror) {
            for (auto& c : corners) c[1] = 2 - c[1];
            std::reverse(corners.begin(), corners.end()); // a mirror turns the winding
        }
        append_obj_face(obj, count, corners, material, group);
    };
    const bool m = mirrored;
    face({{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}}, "floor", "grey", m);   // up
    face({{0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}}, "ceiling", "grey", m); // down
    face({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, "back", "grey", m);    // +z
    face({{0, 0, 2}, {0, 2, 2}, {2, 2, 2}, {2, 0, 2}}, "front", "grey", m);   // -z
    face({{0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2}}, "left", "grey", m);    // +x
    face({{2, 0, 0}, {2, 0, 2}, {2, 2, 2}, {2, 2, 0}}, "right", "grey", m);   // -x
    face({{0.75, 1.99, 0.75}, {1.25, 1.99, 0.75}, {1.25, 1.99, 1.25}, {0.75, 1.99, 1.25}}, "lamp",
         "lamp", m); // down
    face({{0.5, 1, 0.5}, {0.5, 1, 1.5}, {1.5, 1, 1.5}, {1.5, 1, 0.5}}, "sheet", "paper", false);
    return obj;
}

struct Solved {
    radfmt::MeshData mesh;
    std::vector<radfmt::Rgb> radiosity;
};

Solved solve(const std::string& obj, const std::vector<std::string>& two_sided) {
    const auto dir = temp_dir("two_sided");
    write_text(dir / "scene.mtl", kMaterials);
    write_text(dir / "scene.obj", obj);
    rad::SubdivisionOptions options;
    options.max_edge = 0.25;
    Solved s;
    s.mesh = rad::subdivide(rad::load_obj(dir / "scene.obj"), options);
    if (!two_sided.empty()) rad::make_two_sided(s.mesh, two_sided, false);
    rad::FormFactorOptions ff_options;
    ff_options.quiet = true;
    ff_options.visibility_rays = 4;
    const auto ff = rad::compute_form_factors(s.mesh, ff_options);
    rad::SolveControl control;
    control.tolerance = 1e-9;
    control.max_iterations = 1000;
    const auto result =
        rad::solver("gs").solve(rad::make_operator(s.mesh, ff), rad::emission_of(s.mesh), control);
    s.radiosity = rad::to_rgb(result.radiosity);
    return s;
}

// Mean radiosity (red) of the sheet's patches facing up (+1) or down (-1).
double sheet_mean(const Solved& s, double facing) {
    double sum = 0, area = 0;
    const auto sheet =
        std::find(s.mesh.groups.begin(), s.mesh.groups.end(), "sheet") - s.mesh.groups.begin();
    for (std::size_t i = 0; i < s.mesh.patches.size(); ++i) {
        const auto& p = s.mesh.patches[i];
        if (p.group != static_cast<std::uint32_t>(sheet) || p.normal[1] * facing < 0.5) continue;
        sum += s.radiosity[i][0] * p.area;
        area += p.area;
    }
    return area > 0 ? sum / area : 0;
}

} // namespace

TEST_CASE("a two-sided sheet lit from its back equals the mirror image of one lit from its front") {
    const auto front_lit = solve(room_with_sheet(false), {"sheet"});
    const auto back_lit = solve(room_with_sheet(true), {"paper"}); // by material this time
    // Every sheet patch has its back, paired by find_twins.
    const auto twins = rad::find_twins(front_lit.mesh);
    std::size_t paired = 0;
    for (std::size_t i = 0; i < twins.size(); ++i) paired += twins[i] >= 0;
    CHECK(paired == 2 * 16);

    const double lit_front = sheet_mean(front_lit, +1), dark_back = sheet_mean(front_lit, -1);
    const double lit_back = sheet_mean(back_lit, -1), dark_front = sheet_mean(back_lit, +1);
    CAPTURE(lit_front, dark_back, lit_back, dark_front);
    CHECK(lit_front > 3 * dark_back); // the lamp's side is the bright one
    CHECK(lit_back == Approx(lit_front).epsilon(0.01));
    CHECK(dark_front == Approx(dark_back).epsilon(0.01));

    // Patch by patch: the mirror image of each front patch in the first scene is the back
    // patch at the same place in the second.
    for (std::size_t i = 0; i < front_lit.mesh.patches.size(); ++i) {
        const auto& p = front_lit.mesh.patches[i];
        if (front_lit.mesh.groups[p.group] != "sheet") continue;
        bool found = false;
        for (std::size_t j = 0; j < back_lit.mesh.patches.size(); ++j) {
            const auto& q = back_lit.mesh.patches[j];
            if (rad::length(q.centroid - p.centroid) > 1e-9 || q.normal[1] * p.normal[1] > 0)
                continue;
            found = true;
            CHECK(back_lit.radiosity[j][0] == Approx(front_lit.radiosity[i][0]).epsilon(0.03));
        }
        CHECK(found);
    }
}

TEST_CASE("a one-sided sheet lit from its back stays black there; two-sided it does not") {
    const auto one_sided = solve(room_with_sheet(true), {});
    const auto two_sided = solve(room_with_sheet(true), {"sheet"});
    // One-sided, the sheet's only side faces away from the lamp and there is no patch
    // facing it: the light that reaches the sheet from below is lost, so even the upper
    // half of the room (which the sheet's top sees) is darker than with a reflecting back.
    CHECK(sheet_mean(one_sided, -1) == 0);
    CHECK(sheet_mean(one_sided, +1) < sheet_mean(two_sided, +1));
    CHECK(sheet_mean(two_sided, -1) > 3 * sheet_mean(two_sided, +1));
}

TEST_CASE("--two-sided selects groups, materials or all; emitters' backs do not emit") {
    auto mesh = rad::subdivide(scene_from_obj(room_with_sheet(false).substr(17), kMaterials),
                               rad::SubdivisionOptions{});
    const std::size_t n = mesh.patches.size();
    CHECK_THROWS_WITH(rad::make_two_sided(mesh, {"shet"}, false),
                      Catch::Contains("'shet' is neither a group nor a material") &&
                          Catch::Contains("sheet") && Catch::Contains("paper"));
    auto all = mesh;
    const auto report = rad::make_two_sided(all, {"all"}, false);
    CHECK(report.back_patches == n);
    CHECK(report.unlit_back_materials == std::vector<std::string>{"lamp"});
    // The lamp's back has a copy of the lamp material without emission.
    const auto& back_material = all.materials[all.patches[n + 6].material]; // patch 6: the lamp
    CHECK(back_material.name == "lamp.back");
    CHECK(back_material.emission == radfmt::Rgb{});
    CHECK(back_material.reflectance == mesh.materials[mesh.patches[6].material].reflectance);
    // Twice is once: patches that already have a back are left alone.
    CHECK(rad::make_two_sided(all, {"all"}, false).back_patches == 0);
    auto both = mesh;
    rad::make_two_sided(both, {"lamp"}, true);
    REQUIRE(both.patches.size() == n + 1);
    CHECK(both.materials[both.patches.back().material].name == "lamp");
}

TEST_CASE("a polygon patch's back keeps its first corner, so it stays star-shaped from it") {
    auto mesh = polygon_under_square({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 3,
                                     {5.0 / 6, 5.0 / 6, 0});
    REQUIRE(rad::make_two_sided(mesh, {"all"}, false).back_patches == 2);
    const auto& back = mesh.patches[2];
    REQUIRE(back.is_polygon());
    const auto front = mesh.corners(0), reversed = mesh.corners(2);
    CHECK(std::vector<std::uint32_t>(reversed.begin(), reversed.end()) ==
          std::vector<std::uint32_t>{front[0], front[5], front[4], front[3], front[2], front[1]});
    CHECK(back.normal == radfmt::Vec3{0, 0, -1});
    CHECK(rad::find_twins(mesh)[0] == 2);
    // The reader checks the fan from the first corner: the back is written and read back.
    const auto path = temp_dir("two-sided") / "p.mesh";
    radfmt::write_mesh(path, {}, mesh);
    CHECK(radfmt::read_mesh(path).polygon_count() == 2);
}
