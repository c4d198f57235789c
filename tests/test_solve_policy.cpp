// solve policy: overrides, reflectance checks, row-sum warnings, stopping rules, header.
#include "helpers.hpp"
#include "radiosity/error.hpp"
#include "radiosity/solve_policy.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace testing_helpers;
using Catch::Matchers::Contains;

namespace {
radfmt::MeshData two_material_mesh() {
    return mesh_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                         "usemtl grey\nf 1 2 3 4\nusemtl lamp\nf 5 8 7 6\n");
}

radfmt::FormFactorData rows_summing_to(std::vector<std::vector<float>> rows) {
    radfmt::FormFactorData ff;
    ff.patch_count = rows.size();
    ff.row_start.push_back(0);
    for (const auto& row : rows) {
        for (std::size_t j = 0; j < row.size(); ++j) {
            ff.columns.push_back(static_cast<std::uint32_t>(j));
            ff.values.push_back(row[j]);
        }
        ff.row_start.push_back(ff.columns.size());
    }
    return ff;
}
} // namespace

TEST_CASE("material overrides: grey and RGB values, errors name the option and value") {
    CHECK(rad::parse_material_override("lamp=1,2,3", "--emission").value == radfmt::Rgb{1, 2, 3});
    CHECK(rad::parse_material_override("lamp=0.5", "--emission").value ==
          radfmt::Rgb{0.5, 0.5, 0.5});
    CHECK_THROWS_WITH(rad::parse_material_override("lamp", "--emission"),
                      Contains("--emission: 'lamp' is not MATERIAL=r,g,b"));
    CHECK_THROWS_WITH(rad::parse_material_override("lamp=1,x,3", "--emission"),
                      Contains("'x' in 'lamp=1,x,3' is not a number"));
    CHECK_THROWS_WITH(rad::parse_material_override("lamp=1,nan,3", "--emission"),
                      Contains("is not a number"));
    CHECK_THROWS_WITH(rad::parse_material_override("lamp=1,2", "--reflectance"),
                      Contains("needs 1 or 3 values"));
    CHECK_THROWS_WITH(rad::parse_material_override("lamp=1,2,3,4", "--reflectance"),
                      Contains("more than 3"));
    CHECK_THROWS_WITH(rad::parse_material_override("lamp=-1", "--reflectance"),
                      Contains("non-negative"));
}

TEST_CASE("overrides change the materials and are recorded in the header") {
    auto mesh = two_material_mesh();
    rad::SolveRequest request;
    request.emission_overrides = {"lamp=1,2,3"};
    request.reflectance_overrides = {"grey=0.25"};
    request.emission_scale = 2;
    radfmt::Header header;
    rad::apply_material_overrides(mesh, request, header);
    CHECK(mesh.materials[1].emission == radfmt::Rgb{2, 4, 6});
    CHECK(mesh.materials[0].reflectance == radfmt::Rgb{0.25, 0.25, 0.25});
    REQUIRE(header.find("override.emission.lamp"));
    CHECK(*header.find("override.emission.lamp") == "1,2,3");
    CHECK(*header.find("override.reflectance.grey") == "0.25,0.25,0.25");
    CHECK(*header.find("override.emission_scale") == "2");

    request.emission_overrides = {"nothere=1"};
    CHECK_THROWS_WITH(rad::apply_material_overrides(mesh, request, header),
                      Contains("no material or group 'nothere'") &&
                          Contains("materials: grey, lamp"));
    request.emission_overrides = {};
    request.emission_scale = -1;
    CHECK_THROWS_AS(rad::apply_material_overrides(mesh, request, header), rad::InputError);
}

TEST_CASE("reflectances >= 1 are listed all at once with their fix, unless forced") {
    auto mesh = two_material_mesh();
    mesh.materials[0].reflectance = {1, 0.5, 0.5};
    mesh.materials[1].reflectance = {0.2, 1.5, 0.2};
    try {
        rad::check_reflectances(mesh, false);
        FAIL("no error");
    } catch (const rad::InputError& e) {
        const std::string text = e.what();
        CHECK_THAT(text, Contains("may not converge"));
        CHECK_THAT(text, Contains("'grey'") && Contains("--reflectance grey=0.95,0.5,0.5"));
        CHECK_THAT(text, Contains("'lamp'") && Contains("--reflectance lamp=0.2,0.95,0.2"));
    }
    CHECK_NOTHROW(rad::check_reflectances(mesh, true));
}

TEST_CASE("warnings: nothing emits, rows above one") {
    auto mesh = two_material_mesh();
    const auto fine = rows_summing_to({{0, 0.5f}, {0.5f, 0}});
    CHECK(rad::solve_warnings(mesh, fine, "x.ff", 0.01).empty());
    const auto heavy = rows_summing_to({{0, 1.2f}, {0.5f, 0}});
    const auto report = rad::check_row_sums(heavy, 0.01);
    CHECK(report.rows_above == 1);
    CHECK(report.largest == Approx(1.2));
    const auto warnings = rad::solve_warnings(mesh, heavy, "x.ff", 0.01);
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Contains("1 form-factor row(s) of x.ff sum above 1 + 0.01"));
    mesh.materials[1].emission = {0, 0, 0};
    CHECK_FALSE(rad::any_emitter(mesh));
    CHECK_THAT(rad::solve_warnings(mesh, fine, "x.ff", 0.01).at(0), Contains("no patch emits"));
}

TEST_CASE("stopping rules: defaults per solver, sweeps for shooting solvers, exact counts") {
    rad::SolveRequest request;
    auto control = rad::stop_rule(rad::solver("gs"), request, 100);
    CHECK(control.max_iterations == 100000);
    CHECK(control.tolerance == 1e-6);
    control = rad::stop_rule(rad::solver("pr"), request, 100);
    CHECK(control.max_iterations == 100000); // 1000 sweeps-equivalent
    request.iterations = 10;                 // without --tolerance: exactly 10
    CHECK(rad::stop_rule(rad::solver("gs"), request, 100).tolerance == 0);
    request.tolerance_given = true;
    CHECK(rad::stop_rule(rad::solver("gs"), request, 100).tolerance == 1e-6);
    request = {};
    request.sweeps = 2.5;
    CHECK(rad::stop_rule(rad::solver("apr"), request, 100).max_iterations == 250);
    CHECK_THROWS_WITH(rad::stop_rule(rad::solver("gs"), request, 100),
                      Contains("--sweeps applies to shooting solvers"));
}

TEST_CASE("the header records the method, the input hashes, then the result") {
    const auto mesh = two_material_mesh();
    radfmt::Header ff_header;
    ff_header.body_hash = "xxh64:00000000000000ff";
    rad::SolveRequest request;
    request.method = "apr";
    radfmt::Header header;
    rad::record_solve_inputs(header, request, mesh.geometry_hash(), ff_header);
    rad::SolveResult result;
    result.iterations = 12;
    result.residual = 0.125;
    rad::record_solve_result(header, rad::solver("apr"), result);
    std::vector<std::string> keys;
    for (const auto& [k, v] : header.fields) keys.push_back(k);
    CHECK(keys == std::vector<std::string>{"method", "mesh_geometry_hash", "form_factor_hash",
                                           "iterations", "unshot_fraction"});
    CHECK(*header.find("mesh_geometry_hash") == mesh.geometry_hash());
    CHECK(*header.find("form_factor_hash") == "xxh64:00000000000000ff");
    CHECK(*header.find("unshot_fraction") == "0.125");
}

TEST_CASE("--emission names a group when no material has the name (an OBJ without materials)") {
    // Two groups of one material ("default" OBJ material from no usemtl): light the ceiling.
    auto mesh =
        mesh_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                      "g floor\nf 1 2 3 4\ng ceiling\nf 5 8 7 6\n");
    REQUIRE(std::find(mesh.groups.begin(), mesh.groups.end(), "ceiling") != mesh.groups.end());
    rad::SolveRequest request;
    request.emission_overrides = {"ceiling=4,5,6"};
    radfmt::Header header;
    std::vector<std::string> notes;
    rad::apply_material_overrides(mesh, request, header, &notes);
    for (const auto& p : mesh.patches) {
        const auto& m = mesh.materials[p.material];
        const bool ceiling = mesh.groups[p.group] == "ceiling";
        CHECK(m.emits() == ceiling);
        if (ceiling) CHECK(m.emission == radfmt::Rgb{4, 5, 6});
        if (ceiling) CHECK(m.name == "ceiling");
    }
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Contains("group 'ceiling'") && Contains("emits 4,5,6"));
    CHECK(*header.find("override.emission.ceiling") == "4,5,6");
    // What reads the solution replays it from the header, the same way.
    auto replay =
        mesh_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                      "g floor\nf 1 2 3 4\ng ceiling\nf 5 8 7 6\n");
    rad::apply_recorded_overrides(replay, header);
    for (std::size_t i = 0; i < replay.patches.size(); ++i)
        CHECK(replay.materials[replay.patches[i].material].emission ==
              mesh.materials[mesh.patches[i].material].emission);
}
