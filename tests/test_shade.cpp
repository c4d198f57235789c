// rad-shade: rasteriser values, perspective correctness, smoothing, EXR/PNG/PLY output.
#include "helpers.hpp"
#include "radiosity/shade.hpp"

#include <catch2/catch.hpp>
#include <png.h>

using namespace testing_helpers;
using radfmt::Rgb;
using rad::operator-;
using rad::operator+;
using rad::operator*;

namespace {

radfmt::MeshData quad(const std::array<radfmt::Vec3, 4>& corners) {
    radfmt::MeshData m;
    m.vertices.assign(corners.begin(), corners.end());
    radfmt::Patch p;
    p.corners = {0, 1, 2, 3};
    p.area = 1;
    p.normal = rad::normalized(rad::cross(corners[1] - corners[0], corners[2] - corners[0]));
    p.centroid = (corners[0] + corners[1] + corners[2] + corners[3]) * 0.25;
    m.patches = {p};
    m.groups = {"g"};
    m.materials = {{"m", {0.5, 0.5, 0.5}, {0, 0, 0}, {}}};
    return m;
}

float pixel(const rad::Image& image, int x, int y, int c = 0) {
    return image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x) + c];
}

rad::View straight_view() {
    return rad::parse_view("-vp 0 0 0 -vd 0 0 -1 -vu 0 1 0 -vh 90 -vv 90", {"test"});
}

// Two patches sharing the edge x = 1, facing +z: A = [0, 1] x [0, 1] (area 1) and
// B = [1, 4] x [0, 1] (area 3), one material and group.
radfmt::MeshData two_patches() {
    radfmt::MeshData m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0}};
    radfmt::Patch a, b;
    a.corners = {0, 1, 2, 3};
    a.area = 1;
    a.normal = {0, 0, 1};
    b.corners = {1, 4, 5, 2};
    b.area = 3;
    b.normal = {0, 0, 1};
    m.patches = {a, b};
    m.materials = {{"m", {0.5, 0.5, 0.5}, {0, 0, 0}, {}}};
    m.groups = {"g"};
    return m;
}
} // namespace

TEST_CASE("a quad filling the view shows the interpolated vertex values") {
    // Looking down -z (so +x is right), z = -1 and a 90 degree view: the quad covers the image
    // exactly. Value f = 1 + (x + y) / 2.
    const auto mesh = quad({radfmt::Vec3{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}});
    std::vector<std::array<Rgb, 4>> corners{
        {Rgb{0, 0, 0}, Rgb{1, 1, 1}, Rgb{2, 2, 2}, Rgb{1, 1, 1}}};
    const int n = 64;
    const auto image = rad::render(mesh, corners, straight_view(), n, n, 1);
    CHECK(image.covered_pixels == n * n);
    auto expected = [&](int x, int y) {
        const double sx = (x + 0.5) / n * 2 - 1, sy = 1 - (y + 0.5) / n * 2;
        return 1 + (sx + sy) / 2;
    };
    for (auto [x, y] :
         {std::pair{0, 0}, {n - 1, 0}, {0, n - 1}, {n - 1, n - 1}, {n / 2, n / 2}, {10, 50}})
        CHECK(pixel(image, x, y) == Approx(expected(x, y)).margin(1e-5));
}

TEST_CASE("a polygon patch, not convex, is drawn as the surface it covers") {
    // An L at z = -1 filling the view but for its upper right quadrant, star-shaped from its
    // first corner, with the corner values 1 + x + 2y: a linear value, which any correct split
    // into triangles shows exactly at every pixel it covers.
    radfmt::MeshData mesh;
    mesh.groups = {"g"};
    mesh.materials = {{"m", {0.5, 0.5, 0.5}, {0, 0, 0}, {}}};
    rad::CornerColours corners;
    std::vector<radfmt::Vec3> outline;
    for (const auto& [x, y] :
         std::vector<std::array<double, 2>>{{-1, -1}, {1, -1}, {1, 0}, {0, 0}, {0, 1}, {-1, 1}}) {
        outline.push_back({x, y, -1});
        const double value = 1 + x + 2 * y;
        corners.polygon_corners.push_back(Rgb{value, value, value});
    }
    add_polygon_patch(mesh, outline, 3, {-1.0 / 6, -1.0 / 6, -1}, {0, 0, 1});
    corners.patches.resize(1);
    const int n = 64;
    const auto image = rad::render(mesh, corners, straight_view(), n, n, 1);
    CHECK(image.covered_pixels == 3 * n * n / 4);
    for (int y = 0; y < n; y += 3)
        for (int x = 0; x < n; x += 3) {
            const double sx = (x + 0.5) / n * 2 - 1, sy = 1 - (y + 0.5) / n * 2;
            CAPTURE(x, y);
            CHECK(pixel(image, x, y) ==
                  Approx(sx > 0 && sy > 0 ? 0 : 1 + sx + 2 * sy).margin(1e-5));
        }
    // Smoothing gives a polygon's corners their values as any patch's.
    const auto flat = rad::corner_colours(mesh, {Rgb{3, 3, 3}}, rad::Smoothing::Flat);
    const auto area = rad::corner_colours(mesh, {Rgb{3, 3, 3}}, rad::Smoothing::Area);
    for (std::size_t k = 0; k < 6; ++k) {
        CHECK(flat.at(mesh, 0, k) == Rgb{3, 3, 3});
        CHECK(area.at(mesh, 0, k) == Rgb{3, 3, 3});
    }
}

TEST_CASE("smoothing kept to each patch's mean: the slope stays, the mean is the patch's") {
    // A (area 1, value 1) and B (area 3, value 3) side by side, and a polygon patch apart
    // (value 2): averaged corners give A a mean of 1.5 and B 2.5; scaled back, each has its
    // own mean again and keeps its slope towards the other.
    auto m = two_patches();
    add_polygon_patch(m, {{5, 0, 0}, {7, 0, 0}, {7, 1, 0}, {6, 1, 0}, {5, 2, 0}}, 2.5,
                      {5.9, 0.8, 0}, {0, 0, 1});
    const std::vector<Rgb> values{{1, 1, 1}, {3, 3, 3}, {2, 2, 2}};
    auto corners = rad::corner_colours(m, values, rad::Smoothing::Average);
    rad::keep_patch_means(m, values, corners);
    CHECK((corners[0][0][0] + corners[0][1][0] + corners[0][2][0] + corners[0][3][0]) / 4 ==
          Approx(1));
    CHECK((corners[1][0][0] + corners[1][1][0] + corners[1][2][0] + corners[1][3][0]) / 4 ==
          Approx(3));
    CHECK(corners[0][1][0] > corners[0][0][0]); // A still rises towards B
    CHECK(corners[1][0][0] < corners[1][1][0]); // B still falls towards A
    for (std::size_t k = 0; k < 5; ++k) CHECK(corners.at(m, 2, k)[0] == Approx(2));
    // A black patch stays black; one whose corners average to nothing takes its value.
    auto zero = rad::corner_colours(m, {{0, 0, 0}, {3, 3, 3}, {2, 2, 2}}, rad::Smoothing::Average);
    rad::keep_patch_means(m, {{0, 0, 0}, {3, 3, 3}, {2, 2, 2}}, zero);
    for (std::size_t k = 0; k < 4; ++k) CHECK(zero[0][k][0] == 0);
}

TEST_CASE("interpolation is perspective-correct") {
    // A plane receding in depth, coloured by its own depth: every pixel must show the depth
    // where its ray meets the plane (screen-space interpolation would not).
    const auto mesh = quad({radfmt::Vec3{-4, -1, -1}, {4, -1, -1}, {4, -1, -9}, {-4, -1, -9}});
    std::vector<std::array<Rgb, 4>> corners{
        {Rgb{1, 1, 1}, Rgb{1, 1, 1}, Rgb{9, 9, 9}, Rgb{9, 9, 9}}};
    const int n = 64;
    const auto image = rad::render(mesh, corners, straight_view(), n, n, 1);
    for (int y = n / 2 + 2; y < n; y += 5) {
        const double sy = 1 - (y + 0.5) / n * 2; // ray (sx, sy, -1) meets y = -1 at depth -1/sy
        const double depth = -1 / sy;
        if (depth > 9 || depth < 1) continue;
        CHECK(pixel(image, n / 2, y) == Approx(depth).epsilon(1e-5));
    }
    CHECK(pixel(image, n / 2, 5) == 0); // above the horizon: background
}

TEST_CASE("the z-buffer keeps the nearest surface and supersampling averages") {
    auto mesh = quad({radfmt::Vec3{-1, -1, -2}, {1.25, -1, -2}, {1.25, 1, -2}, {-1, 1, -2}});
    mesh.vertices.insert(mesh.vertices.end(), {{-1, -1, -1}, {0, -1, -1}, {0, 1, -1}, {-1, 1, -1}});
    radfmt::Patch near = mesh.patches[0];
    near.corners = {4, 5, 6, 7};
    mesh.patches.push_back(near);
    const auto corners =
        rad::corner_colours(mesh, {Rgb{1, 1, 1}, Rgb{5, 5, 5}}, rad::Smoothing::Flat);
    const auto image = rad::render(mesh, corners, straight_view(), 8, 8, 4);
    CHECK(pixel(image, 1, 4) == Approx(5)); // near half on the left
    CHECK(pixel(image, 5, 4) == Approx(1)); // far quad on the right
    // The far quad ends at screen x = 0.625, halfway across pixel 6: half of its 4 x 4
    // subsamples see it.
    CHECK(pixel(image, 6, 4) == Approx(0.5));
}

TEST_CASE("back faces are counted and marked; a two-sided sheet shows the side facing the camera") {
    // Facing the camera (wound counter-clockwise as seen from it): no back face.
    const auto facing = quad({radfmt::Vec3{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}});
    std::vector<std::array<Rgb, 4>> one{{Rgb{2, 2, 2}, Rgb{2, 2, 2}, Rgb{2, 2, 2}, Rgb{2, 2, 2}}};
    const int n = 16;
    CHECK(rad::render(facing, one, straight_view(), n, n, 2).back_face_pixels == 0);
    // Wound the other way it faces away: every pixel shows its back, and marking paints them.
    const auto away = quad({radfmt::Vec3{-1, 1, -1}, {1, 1, -1}, {1, -1, -1}, {-1, -1, -1}});
    auto image = rad::render(away, one, straight_view(), n, n, 2);
    CHECK(image.back_face_pixels == n * n);
    CHECK(pixel(image, 3, 3) == Approx(2)); // shown as it is by default
    rad::mark_back_faces(image, Rgb{1, 0, 1});
    CHECK(pixel(image, 3, 3, 0) == 1);
    CHECK(pixel(image, 3, 3, 1) == 0);

    // A two-sided sheet: front (value 1) and back (value 7) on one spot, in either order.
    for (bool back_first : {false, true}) {
        CAPTURE(back_first);
        auto sheet = facing;
        radfmt::Patch back = sheet.patches[0];
        back.corners = {3, 2, 1, 0};
        back.normal = sheet.patches[0].normal * -1.0;
        sheet.patches.push_back(back);
        std::vector<Rgb> values{Rgb{1, 1, 1}, Rgb{7, 7, 7}};
        if (back_first) {
            std::swap(sheet.patches[0], sheet.patches[1]);
            std::swap(values[0], values[1]);
        }
        // Smoothing never mixes the two sides.
        const auto corners = rad::corner_colours(sheet, values, rad::Smoothing::Average);
        const auto from_front = rad::render(sheet, corners, straight_view(), n, n, 1);
        CHECK(from_front.back_face_pixels == 0);
        CHECK(pixel(from_front, n / 2, n / 2) == Approx(1));
        const auto behind =
            rad::parse_view("-vp 0 0 -2 -vd 0 0 1 -vu 0 1 0 -vh 90 -vv 90", {"test"});
        const auto from_behind = rad::render(sheet, corners, behind, n, n, 1);
        CHECK(from_behind.back_face_pixels == 0);
        CHECK(pixel(from_behind, n / 2, n / 2) == Approx(7));
    }
}

TEST_CASE("smoothing: averages, area weights, creases and flat") {
    // Two patches sharing the edge x = 1: A (area 1, value 1) and B (area 3, value 3).
    auto m = two_patches();
    const std::vector<Rgb> values{{1, 1, 1}, {3, 3, 3}};
    const auto average = rad::corner_colours(m, values, rad::Smoothing::Average);
    CHECK(average[0][0][0] == 1); // vertex 0 touches A only
    CHECK(average[0][1][0] == 2); // shared vertex: (1 + 3) / 2
    CHECK(average[1][0][0] == 2);
    const auto area = rad::corner_colours(m, values, rad::Smoothing::Area);
    CHECK(area[0][1][0] == Approx((1 * 1 + 3 * 3) / 4.0));
    const auto flat = rad::corner_colours(m, values, rad::Smoothing::Flat);
    CHECK(flat[0][1][0] == 1);
    CHECK(flat[1][0][0] == 3);
    // Fold B up by 90 degrees: crease-aware smoothing keeps the step at the edge.
    m.vertices[4] = {1, 0, 3};
    m.vertices[5] = {1, 1, 3};
    m.patches[1].normal = {-1, 0, 0};
    const auto crease = rad::corner_colours(m, values, rad::Smoothing::Crease, 30);
    CHECK(crease[0][1][0] == 1);
    CHECK(crease[1][0][0] == 3);
    // ... and at a material boundary even when coplanar.
    m.vertices[4] = {4, 0, 0};
    m.vertices[5] = {4, 1, 0};
    m.patches[1].normal = {0, 0, 1};
    m.materials.push_back({"n", {0.5, 0.5, 0.5}, {0, 0, 0}, {}});
    m.patches[1].material = 1;
    const auto material = rad::corner_colours(m, values, rad::Smoothing::Crease, 30);
    CHECK(material[0][1][0] == 1);
    CHECK(rad::corner_colours(m, values, rad::Smoothing::Average)[0][1][0] == 2);
    // ... and at a group boundary with the same material (two walls of one paint).
    m.patches[1].material = 0;
    m.groups.push_back("h");
    m.patches[1].group = 1;
    const auto group = rad::corner_colours(m, values, rad::Smoothing::Crease, 30);
    CHECK(group[0][1][0] == 1);
    CHECK(group[1][0][0] == 3);
}

TEST_CASE("EXR, PNG and PLY outputs read back with the expected values") {
    const auto dir = temp_dir("shade");
    const auto mesh = quad({radfmt::Vec3{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}});
    std::vector<std::array<Rgb, 4>> corners{
        {Rgb{0, 0.1, 0.2}, Rgb{1, 1.1, 1.2}, Rgb{2, 2.1, 2.2}, Rgb{1, 1.1, 1.2}}};
    const auto image = rad::render(mesh, corners, straight_view(), 16, 12, 2);
    const auto exr = (dir / "a.exr").string();
    rad::write_exr(exr, image, {{"radiosity:provenance", "1. rad-mesh x\n2. rad-shade y\n"}});
    std::map<std::string, std::string> attributes;
    const auto back = rad::read_exr(exr, &attributes);
    CHECK(back.width == 16);
    CHECK(back.height == 12);
    CHECK(back.rgb == image.rgb);
    CHECK(attributes["radiosity:provenance"] == "1. rad-mesh x\n2. rad-shade y\n");

    const auto png = (dir / "a.png").string();
    rad::write_png(png, image, 0.4);
    png_image read{};
    read.version = PNG_IMAGE_VERSION;
    REQUIRE(png_image_begin_read_from_file(&read, png.c_str()));
    read.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(read));
    REQUIRE(png_image_finish_read(&read, nullptr, pixels.data(), 0, nullptr));
    CHECK(read.width == 16);
    for (std::size_t i = 0; i < pixels.size(); ++i)
        CHECK(int(pixels[i]) == int(rad::to_srgb8(image.rgb[i] * 0.4)));

    const auto ply = (dir / "a.ply").string();
    rad::write_ply(ply, mesh, corners, 0.4);
    std::ifstream in(ply);
    std::string line;
    std::vector<std::string> lines;
    while (std::getline(in, line)) lines.push_back(line);
    CHECK(lines[0] == "ply");
    CHECK(std::find(lines.begin(), lines.end(), "element vertex 4") != lines.end());
    const auto end = std::find(lines.begin(), lines.end(), "end_header");
    REQUIRE(end != lines.end());
    std::istringstream third(*(end + 3)); // corner 2: value 2, 2.1, 2.2
    double x, y, z, br, bg, bb;
    int r, g, b;
    third >> x >> y >> z >> r >> g >> b >> br >> bg >> bb;
    CHECK(r == int(rad::to_srgb8(2 * 0.4)));
    CHECK(bb == Approx(2.2));
    CHECK(*(end + 5) == "4 0 1 2 3");
}

TEST_CASE("bad views are refused") {
    CHECK_THROWS_WITH(rad::parse_view("-vd 0 0 0", {"v"}), Catch::Contains("zero"));
    CHECK_THROWS_WITH(rad::parse_view("-vd 0 1 0 -vu 0 2 0", {"v"}), Catch::Contains("parallel"));
    CHECK_THROWS_WITH(rad::parse_view("-vh 180", {"v"}), Catch::Contains("between 0 and 180"));
    CHECK_THROWS_WITH(rad::parse_view("-vp 1 2", {"v"}), Catch::Contains("needs a number"));
    CHECK_THROWS_WITH(rad::parse_view("-vz 1", {"v"}), Catch::Contains("unknown view option"));
}
