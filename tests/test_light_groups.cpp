// Light groups: superposition (a mix of group solutions equals a solve with those emissions),
// for every solver; group definitions and their errors; mixing and its errors.
#include "helpers.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/solver.hpp"

#include <catch2/catch.hpp>

using namespace testing_helpers;
using Catch::Matchers::Contains;

namespace {

// A 2 m room with a lamp panel on the ceiling and a window in a wall, and a block.
const std::string kMaterials = "newmtl wall\nKd 0.6 0.55 0.5\nnewmtl lamp\nKd 0.5 0.5 0.5\n"
                               "Ke 20 15 10\nnewmtl window\nKd 0.3 0.3 0.3\nKe 5 6 9\n"
                               "newmtl dark\nKd 0.2 0.2 0.2\n";

radfmt::MeshData room() {
    std::string obj;
    int count = 0;
    auto quad = [&](std::vector<rad::Vec3> c, const char* material) {
        append_obj_face(obj, count, c, material);
    };
    quad({{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}}, "wall");   // floor, up
    quad({{0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}}, "wall");   // ceiling, down
    quad({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, "window"); // back, +z
    quad({{0, 0, 2}, {0, 2, 2}, {2, 2, 2}, {2, 0, 2}}, "wall");   // front, -z
    quad({{0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2}}, "dark");   // left, +x
    quad({{2, 0, 0}, {2, 0, 2}, {2, 2, 2}, {2, 2, 0}}, "wall");   // right, -x
    quad({{0.7, 1.99, 0.7}, {1.3, 1.99, 0.7}, {1.3, 1.99, 1.3}, {0.7, 1.99, 1.3}}, "lamp");
    rad::SubdivisionOptions options;
    options.max_edge = 0.5;
    return rad::subdivide(scene_from_obj(obj, kMaterials), options);
}

} // namespace

TEST_CASE("a mix of light groups equals a solve of the mixed emission, for every solver") {
    auto mesh = room();
    rad::FormFactorOptions ff_options;
    ff_options.quiet = true;
    const auto ff = rad::compute_form_factors(mesh, ff_options);
    const auto groups = rad::light_groups(mesh, {});
    REQUIRE(groups.size() == 2);
    CHECK(groups[0].name == "lamp");
    CHECK(groups[1].name == "window");
    const auto op = rad::make_operator(mesh, ff);
    const auto lamp = std::find_if(mesh.materials.begin(), mesh.materials.end(),
                                   [](const auto& m) { return m.name == "lamp"; }) -
                      mesh.materials.begin();
    const auto window = std::find_if(mesh.materials.begin(), mesh.materials.end(),
                                     [](const auto& m) { return m.name == "window"; }) -
                        mesh.materials.begin();
    const auto base_lamp = mesh.materials[lamp].emission,
               base_window = mesh.materials[window].emission;
    for (const auto& name : rad::solver_names()) {
        CAPTURE(name);
        const auto& solver = rad::solver(name);
        rad::SolveControl control;
        control.tolerance = 1e-13;
        control.max_iterations = solver.shooting() ? 200000 : 2000;
        const auto grouped = rad::radiosity_data(
            solver.solve(op, rad::grouped_emission(mesh, groups), control).radiosity, groups);
        for (const auto& [a, b] : {std::pair{1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {0.3, 2.0}}) {
            CAPTURE(a, b);
            const auto mixed = rad::mix_light_groups(
                grouped, {"lamp=" + std::to_string(a), "window=" + std::to_string(b)}, false,
                "test.rad");
            for (int c = 0; c < 3; ++c) {
                mesh.materials[lamp].emission[c] = a * base_lamp[c];
                mesh.materials[window].emission[c] = b * base_window[c];
            }
            const auto direct =
                rad::to_rgb(solver.solve(op, rad::emission_of(mesh), control).radiosity);
            double worst = 0;
            for (std::size_t i = 0; i < direct.size(); ++i)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(mixed[i][c] - direct[i][c]) /
                                                std::max(1e-9, std::abs(direct[i][c])));
            CHECK(worst < 1e-6);
        }
        for (int c = 0; c < 3; ++c) {
            mesh.materials[lamp].emission[c] = base_lamp[c];
            mesh.materials[window].emission[c] = base_window[c];
        }
        // Weight 1 for every group is the stored total.
        const auto ones = rad::mix_light_groups(grouped, {}, false, "test.rad");
        CHECK(ones == grouped.radiosity);
    }
}

TEST_CASE("light groups: --group definitions, errors, and mixing errors") {
    const auto mesh = room();
    const auto together = rad::light_groups(mesh, {"all=lamp,window"});
    REQUIRE(together.size() == 1);
    CHECK(together[0].name == "all");
    CHECK(together[0].materials.size() == 2);
    const auto renamed = rad::light_groups(mesh, {"ceiling=lamp"});
    REQUIRE(renamed.size() == 2);
    CHECK(renamed[0].name == "ceiling");
    CHECK(renamed[1].name == "window"); // the emitter outside every group keeps its own
    CHECK_THROWS_WITH(rad::light_groups(mesh, {"x=lamb"}),
                      Contains("no material 'lamb'") && Contains("lamp, window"));
    CHECK_THROWS_WITH(rad::light_groups(mesh, {"a=lamp", "b=lamp"}),
                      Contains("already in group 'a'"));
    CHECK_THROWS_WITH(rad::light_groups(mesh, {"a=lamp", "a=window"}),
                      Contains("'a' is defined twice"));
    CHECK_THROWS_WITH(rad::light_groups(mesh, {"walls=wall"}),
                      Contains("none of its materials emits"));
    CHECK_THROWS_WITH(rad::light_groups(mesh, {"nothing"}), Contains("NAME=MATERIAL"));

    radfmt::RadiosityData plain{{{{1, 1, 1}}}};
    CHECK_THROWS_WITH(rad::mix_light_groups(plain, {"lamp=0"}, false, "old.rad"),
                      Contains("old.rad has no light groups") &&
                          Contains("rad-solve --light-groups"));
    radfmt::RadiosityData grouped;
    grouped.radiosity = {{{3, 3, 3}}};
    grouped.group_names = {"lamp", "window"};
    grouped.group_radiosity = {{{1, 1, 1}}, {{2, 2, 2}}};
    CHECK_THROWS_WITH(rad::mix_light_groups(grouped, {"sun=1"}, false, "g.rad"),
                      Contains("no light group 'sun'") && Contains("lamp, window"));
    const auto only = rad::mix_light_groups(grouped, {"window=0.5,1,2"}, true, "g.rad");
    CHECK(only[0] == radfmt::Rgb{{1, 2, 4}});
}
