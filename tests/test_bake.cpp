// rad-bake's library side: charts, atlas packing, lightmap rendering and padding, glb bytes.
#include "helpers.hpp"
#include "radiosity/bake.hpp"
#include "radiosity/error.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <random>

using namespace testing_helpers;
using rad::operator-;

namespace {

// A closed 2 m cube gridded at 0.5 m: six walls of 16 patches.
radfmt::MeshData cube_mesh() {
    return mesh_from_obj(cube_obj(2.0), 0.5);
}

std::vector<radfmt::Rgb> random_radiosity(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.1, 1.0);
    std::vector<radfmt::Rgb> b(n);
    for (auto& v : b) v = {u(rng), u(rng), u(rng)};
    return b;
}

} // namespace

TEST_CASE("charts: each flat wall is one chart, each patch in one chart, lengths kept") {
    const auto mesh = cube_mesh();
    REQUIRE(mesh.patches.size() == 96);
    const auto charts = rad::build_charts(mesh, 20);
    REQUIRE(charts.size() == 6);
    std::vector<int> seen(mesh.patches.size(), 0);
    for (const auto& chart : charts) {
        CHECK(chart.patches.size() == 16);
        CHECK(chart.width == Approx(2.0).margin(1e-9));
        CHECK(chart.height == Approx(2.0).margin(1e-9));
        for (std::size_t i = 0; i < chart.patches.size(); ++i) {
            const auto& p = mesh.patches[chart.patches[i]];
            ++seen[chart.patches[i]];
            for (int k = 0; k < p.corner_count(); ++k) {
                const int n = (k + 1) % p.corner_count();
                const auto& a = chart.corner_uv[i][k];
                const auto& b = chart.corner_uv[i][n];
                const double flat = std::hypot(a[0] - b[0], a[1] - b[1]);
                const double space =
                    rad::length(mesh.vertices[p.corners[k]] - mesh.vertices[p.corners[n]]);
                CHECK(flat == Approx(space).margin(1e-12));
                CHECK(a[0] >= -1e-12);
                CHECK(a[1] >= -1e-12);
            }
        }
    }
    for (int s : seen) CHECK(s == 1);
    // Each wall is its own group: charts never cross groups (smoothing does not either).
    CHECK(rad::build_charts(mesh, 95).size() == 6);
}

TEST_CASE("atlas: rectangles inside the atlas and disjoint; a density too high is refused") {
    const auto mesh = cube_mesh();
    const auto charts = rad::build_charts(mesh, 20);
    const auto layout = rad::pack_atlas(charts, 256, 0, 2);
    CHECK(layout.texels_per_metre > 30); // six 2 m walls in 256^2: about 40 texels a metre
    for (std::size_t a = 0; a < charts.size(); ++a) {
        CHECK(layout.origin[a][0] >= 0);
        CHECK(layout.origin[a][1] >= 0);
        CHECK(layout.origin[a][0] + layout.extent[a][0] <= 256);
        CHECK(layout.origin[a][1] + layout.extent[a][1] <= 256);
        for (std::size_t b = a + 1; b < charts.size(); ++b) {
            const bool apart = layout.origin[a][0] + layout.extent[a][0] <= layout.origin[b][0] ||
                               layout.origin[b][0] + layout.extent[b][0] <= layout.origin[a][0] ||
                               layout.origin[a][1] + layout.extent[a][1] <= layout.origin[b][1] ||
                               layout.origin[b][1] + layout.extent[b][1] <= layout.origin[a][1];
            CHECK(apart);
        }
    }
    CHECK_THROWS_AS(rad::pack_atlas(charts, 256, 1000, 2), rad::InputError);
}

TEST_CASE("lightmap: flat radiosity integrates to each chart's power") {
    const auto mesh = cube_mesh();
    const auto b = random_radiosity(mesh.patches.size(), 7);
    const auto charts = rad::build_charts(mesh, 20);
    const auto layout = rad::pack_atlas(charts, 512, 0, 2);
    const auto corners = rad::corner_colours(mesh, b, rad::Smoothing::Flat);
    const auto map = rad::render_lightmap(mesh, charts, layout, corners);
    const double texel_area = 1 / (layout.texels_per_metre * layout.texels_per_metre);
    for (std::size_t c = 0; c < charts.size(); ++c) {
        double power = 0, area = 0;
        for (const auto i : charts[c].patches) {
            power += mesh.patches[i].area * b[i][0];
            area += mesh.patches[i].area;
        }
        double texels = 0, sum = 0;
        const auto& o = layout.origin[c];
        const auto& e = layout.extent[c];
        for (int y = o[1]; y < o[1] + e[1]; ++y)
            for (int x = o[0]; x < o[0] + e[0]; ++x) {
                const std::size_t t = std::size_t(y) * map.size + x;
                if (map.state[t] != rad::Lightmap::kChart) continue;
                texels += texel_area;
                sum += map.rgb[3 * t] * texel_area;
            }
        // Texel centres inside a 2 m wall at ~80 texels a metre: the area to a texel row.
        CHECK(texels == Approx(area).epsilon(0.03));
        CHECK(sum / texels == Approx(power / area).epsilon(0.01));
    }
}

TEST_CASE("lightmap: every padding texel has the value of a nearest chart texel") {
    const auto mesh = mesh_from_obj(cube_obj(1.0), 0.3); // uneven grid: cells of 1/4 m
    const auto b = random_radiosity(mesh.patches.size(), 3);
    const auto charts = rad::build_charts(mesh, 20);
    const auto layout = rad::pack_atlas(charts, 64, 0, 3);
    const auto map = rad::render_lightmap(mesh, charts, layout,
                                          rad::corner_colours(mesh, b, rad::Smoothing::Crease));
    int padding = 0;
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const auto& o = layout.origin[c];
        const auto& e = layout.extent[c];
        for (int y = o[1]; y < o[1] + e[1]; ++y)
            for (int x = o[0]; x < o[0] + e[0]; ++x) {
                const std::size_t t = std::size_t(y) * map.size + x;
                REQUIRE(map.state[t] != rad::Lightmap::kEmpty); // the rectangle is all filled
                if (map.state[t] != rad::Lightmap::kPadding) continue;
                ++padding;
                int nearest = 1 << 30;
                bool matches = false;
                for (int yy = o[1]; yy < o[1] + e[1]; ++yy)
                    for (int xx = o[0]; xx < o[0] + e[0]; ++xx) {
                        const std::size_t s = std::size_t(yy) * map.size + xx;
                        if (map.state[s] != rad::Lightmap::kChart) continue;
                        const int d = std::max(std::abs(xx - x), std::abs(yy - y));
                        const bool same = std::memcmp(&map.rgb[3 * s], &map.rgb[3 * t], 12) == 0;
                        if (d < nearest)
                            nearest = d, matches = same;
                        else if (d == nearest)
                            matches = matches || same;
                    }
                CHECK(matches);
            }
    }
    CHECK(padding > 0);
}

TEST_CASE("glb: header, chunks, counts and colours as written") {
    const auto mesh = cube_mesh();
    const auto b = random_radiosity(mesh.patches.size(), 11);
    rad::BakeOptions options;
    options.smoothing = rad::Smoothing::Flat;
    options.exposure = 0.5;
    auto result = rad::bake(mesh, b, {}, options);
    result.scene.generator = "test";
    result.scene.extras_json = R"({"note": "x"})";
    const auto path = temp_dir("bake") / "cube.glb";
    const auto glb = rad::baked_glb(result.scene);
    rad::write_file(path.string(), glb.data(), glb.size());

    std::ifstream in(path, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
    auto u32 = [&](std::size_t at) {
        std::uint32_t v;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;
    };
    REQUIRE(bytes.size() > 28);
    CHECK(u32(0) == 0x46546C67);
    CHECK(u32(4) == 2);
    CHECK(u32(8) == bytes.size());
    const std::uint32_t json_size = u32(12);
    CHECK(json_size % 4 == 0);
    const auto doc = nlohmann::json::parse(std::string(bytes.data() + 20, json_size));
    const std::size_t bin_at = 20 + json_size;
    CHECK(u32(bin_at + 4) == 0x004E4942);
    CHECK(doc["asset"]["extras"]["radiosity"]["note"] == "x");
    CHECK(doc["buffers"][0]["byteLength"] == u32(bin_at));

    // One primitive (one material, no twins); 96 quads as 192 triangles.
    const auto& prim = doc["meshes"][0]["primitives"][0];
    CHECK(doc["meshes"][0]["primitives"].size() == 1);
    CHECK(doc["accessors"][prim["indices"].get<int>()]["count"] == 192 * 3);
    const auto& pos = doc["accessors"][prim["attributes"]["POSITION"].get<int>()];
    CHECK(pos["min"] == nlohmann::json({0.0, 0.0, 0.0}));
    CHECK(pos["max"] == nlohmann::json({2.0, 2.0, 2.0}));
    // Flat: every vertex colour is its patch's radiosity times the exposure. Read them back
    // and find each among the patches' values.
    const auto& colour = doc["accessors"][prim["attributes"]["COLOR_0"].get<int>()];
    const auto& view = doc["bufferViews"][colour["bufferView"].get<int>()];
    const std::size_t count = colour["count"];
    CHECK(count == 96 * 4); // flat: no corner shares a colour with another patch's
    for (std::size_t v = 0; v < count; ++v) {
        float c[3];
        std::memcpy(c, bytes.data() + bin_at + 8 + view["byteOffset"].get<std::size_t>() + 12 * v,
                    12);
        bool found = false;
        for (const auto& patch : b)
            found = found || (c[0] == float(patch[0] * 0.5) && c[1] == float(patch[1] * 0.5) &&
                              c[2] == float(patch[2] * 0.5));
        CHECK(found);
    }
}

TEST_CASE("a polygon patch, not convex, bakes as the surface it covers") {
    // An L of 3 m^2 (a polygon patch) under a 2 x 2 m square (a quad).
    const auto mesh = polygon_under_square({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 3,
                                           {5.0 / 6, 5.0 / 6, 0});
    const std::vector<radfmt::Rgb> b{{0.25, 0.5, 0.75}, {1, 1, 1}};
    const auto charts = rad::build_charts(mesh, 20);
    REQUIRE(charts.size() == 2);
    REQUIRE(charts[0].patches == std::vector<std::uint32_t>{0});
    CHECK(charts[0].corner_uv[0].size() == 6);
    const auto layout = rad::pack_atlas(charts, 256, 0, 2);
    const auto map = rad::render_lightmap(mesh, charts, layout,
                                          rad::corner_colours(mesh, b, rad::Smoothing::Flat));
    double texels = 0, sum = 0;
    const double texel_area = 1 / (layout.texels_per_metre * layout.texels_per_metre);
    for (std::size_t t = 0; t < map.state.size(); ++t)
        if (map.state[t] == rad::Lightmap::kChart && map.rgb[3 * t + 2] < 0.9f) {
            texels += texel_area;
            sum += map.rgb[3 * t + 2] * texel_area;
        }
    // Texel centres in the L, not in its bounding square (4 m^2): its area to a texel row.
    CHECK(texels == Approx(3).epsilon(0.03));
    CHECK(sum / texels == Approx(0.75).epsilon(1e-6));
    // The glb: the L as the 4 triangles of its fan, the square as 2.
    rad::BakeOptions options;
    options.smoothing = rad::Smoothing::Flat;
    auto result = rad::bake(mesh, b, {}, options);
    result.scene.generator = "test";
    const auto glb = rad::baked_glb(result.scene);
    std::uint32_t json_size;
    std::memcpy(&json_size, glb.data() + 12, 4);
    const auto doc =
        nlohmann::json::parse(std::string(glb.begin() + 20, glb.begin() + 20 + json_size));
    const auto& prim = doc["meshes"][0]["primitives"][0];
    CHECK(doc["accessors"][prim["indices"].get<int>()]["count"] == (4 + 2) * 3);
    CHECK(doc["accessors"][prim["attributes"]["POSITION"].get<int>()]["count"] == 6 + 4);
}

TEST_CASE("irradiance: albedo times what falls on a patch, plus its emission, gives B back") {
    auto mesh = cube_mesh();
    mesh.materials[0].reflectance = {0.5, 0.25, 0.0}; // a channel that reflects nothing
    mesh.materials[0].emission = {0.1, 0.0, 0.0};
    const auto b = random_radiosity(mesh.patches.size(), 5);
    const auto h = rad::patch_irradiance(mesh, b);
    for (std::size_t i = 0; i < b.size(); ++i) {
        CHECK(0.5 * h[i][0] + 0.1 == Approx(std::max(b[i][0], 0.1)));
        CHECK(0.25 * h[i][1] == Approx(b[i][1]));
        CHECK(h[i][2] == Approx((h[i][0] + h[i][1]) / 2)); // unknown: the other channels' mean
    }
    // Baked with flat smoothing, every chart texel of the irradiance atlas is its patch's H.
    rad::BakeOptions options;
    options.smoothing = rad::Smoothing::Flat;
    options.lightmap_size = 256;
    options.engine_solved = &mesh;
    const auto result = rad::bake(mesh, b, {}, options);
    std::size_t texels = 0;
    for (std::size_t t = 0; t < result.irradiance.state.size(); ++t) {
        if (result.irradiance.state[t] != rad::Lightmap::kChart) continue;
        ++texels;
        bool found = false;
        for (const auto& v : h) found = found || result.irradiance.rgb[3 * t + 1] == float(v[1]);
        CHECK(found);
    }
    CHECK(texels > 256 * 256 / 4); // six walls fill over half the atlas
}
