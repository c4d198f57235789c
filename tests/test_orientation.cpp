// orientation: the checks fire on wrong faces and stay silent on right ones; the fixes work.
#include "helpers.hpp"
#include "radiosity/error.hpp"
#include "radiosity/orientation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>

using namespace testing_helpers;
using Kind = rad::OrientationFinding::Kind;

namespace {
// A closed unit cube with outward faces, each face with its own vertices (as exporters
// write them), offset by (x, y, z). `flip` reverses the faces whose index is in it.
std::string cube(double x, double y, double z, const std::string& group, std::vector<int> flip = {},
                 bool all_flipped = false, int* vertex_count = nullptr) {
    static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::string out = group.empty() ? "" : "g " + group + "\n";
    int base = vertex_count ? *vertex_count : 0;
    for (int f = 0; f < 6; ++f) {
        for (int k = 0; k < 4; ++k) {
            const int c = faces[f][k];
            out += "v " + std::to_string(x + (c & 1)) + " " + std::to_string(y + ((c >> 1) & 1)) +
                   " " + std::to_string(z + ((c >> 2) & 1)) + "\n";
        }
        const bool flipped = all_flipped != (std::find(flip.begin(), flip.end(), f) != flip.end());
        out += "f";
        for (int k = 0; k < 4; ++k) {
            out += ' ';
            out += std::to_string(base + 1 + (flipped ? 3 - k : k));
        }
        out += "\n";
        base += 4;
    }
    if (vertex_count) *vertex_count = base;
    return out;
}

// `obj` with every vertex coordinate x replaced by scale * x + shift.
std::string scaled(const std::string& obj, double scale, double shift) {
    std::string out;
    std::istringstream lines(obj);
    for (std::string line; std::getline(lines, line);) {
        double a, b, c;
        if (std::sscanf(line.c_str(), "v %lf %lf %lf", &a, &b, &c) == 3)
            line = "v " + std::to_string(scale * a + shift) + " " +
                   std::to_string(scale * b + shift) + " " + std::to_string(scale * c + shift);
        out += line + "\n";
    }
    return out;
}

std::vector<rad::OrientationFinding> of_kind(const std::vector<rad::OrientationFinding>& all,
                                             Kind kind) {
    std::vector<rad::OrientationFinding> out;
    for (const auto& f : all)
        if (f.kind == kind) out.push_back(f);
    return out;
}
} // namespace

TEST_CASE("an outward cube inside an inward room gives no finding") {
    int count = 0;
    std::string room = cube(-5, -5, -5, "room", {}, true, &count);
    // Scale the room up: 10 x 10 x 10 around the unit cube.
    std::string obj = scaled(room, 10, 45);
    obj += cube(0, 0, 0, "box", {}, false, &count);
    const auto scene = scene_from_obj("usemtl grey\n" + obj);
    CHECK(rad::check_orientation(scene).empty());
}

TEST_CASE("a room stays a room when an object pokes a little through its wall") {
    // As in McGuire's CornellBox-Water, whose water sticks 4 mm out of a 2 m box: the room's
    // box no longer holds every vertex, but it is still the scene's enclosure.
    int count = 0;
    const std::string room = cube(-5, -5, -5, "room", {}, true, &count);
    std::string obj = scaled(room, 10, 45);            // 10 x 10 x 10 around the unit cube
    obj += cube(4.05, 0, 0, "box", {}, false, &count); // 5 cm through the wall at x = 5
    const auto scene = scene_from_obj("usemtl grey\n" + obj);
    for (const auto& f : rad::check_orientation(scene)) FAIL(rad::describe(f, scene));
}

TEST_CASE("a face wound against its neighbours is found by group and line, and fixed") {
    int count = 0;
    auto scene = scene_from_obj("usemtl grey\n" + cube(0, 0, 0, "box", {2}, false, &count));
    const auto findings = rad::check_orientation(scene);
    const auto against = of_kind(findings, Kind::AgainstNeighbours);
    REQUIRE(against.size() == 1);
    CHECK(against[0].polygons == std::vector<std::size_t>{2});
    CHECK_THAT(rad::describe(against[0], scene),
               Catch::Contains("group box: 1 face(s) wound against their neighbours") &&
                   Catch::Contains("scene.obj:"));
    CHECK(of_kind(findings, Kind::InsideOut).empty());
    const auto flipped = rad::fix_orientation(scene, findings);
    REQUIRE(flipped.size() == 1);
    CHECK(flipped[0].second == 1);
    CHECK(rad::check_orientation(scene).empty());
}

TEST_CASE("a closed object turned inside out is found and turned outward") {
    int count = 0;
    // An inside-out cube next to a right one (so it is not the scene's enclosure).
    const auto first = cube(0, 0, 0, "inside_out", {}, true, &count);
    auto scene = scene_from_obj("usemtl grey\n" + first + cube(3, 0, 0, "fine", {}, false, &count));
    const auto findings = rad::check_orientation(scene);
    const auto inside_out = of_kind(findings, Kind::InsideOut);
    REQUIRE(inside_out.size() == 1);
    CHECK(scene.groups[inside_out[0].group] == "inside_out");
    CHECK(inside_out[0].polygons.size() == 6);
    rad::fix_orientation(scene, findings);
    CHECK(rad::check_orientation(scene).empty());

    SECTION("one face already outward in an inside-out cube: the other five turn") {
        int c2 = 0;
        const auto first2 = cube(0, 0, 0, "mixed", {1}, true, &c2);
        auto mixed =
            scene_from_obj("usemtl grey\n" + first2 + cube(3, 0, 0, "fine", {}, false, &c2));
        const auto f2 = rad::check_orientation(mixed);
        // The one face that disagrees with its neighbours is the right one: the five
        // others are reported, as facing into their object.
        CHECK(of_kind(f2, Kind::AgainstNeighbours).empty());
        REQUIRE(of_kind(f2, Kind::InsideOut).size() == 1);
        CHECK(of_kind(f2, Kind::InsideOut)[0].polygons.size() == 5);
        const auto flipped = rad::fix_orientation(mixed, f2);
        REQUIRE(flipped.size() == 1);
        CHECK(flipped[0].second == 5);
        CHECK(rad::check_orientation(mixed).empty());
    }
}

TEST_CASE("faces wound against their own vn normals are reported, never flipped") {
    auto scene = scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 -1\nusemtl grey\ng sheet\n"
                                "f 1//1 2//1 3//1\n");
    const auto findings = rad::check_orientation(scene);
    REQUIRE(findings.size() == 1);
    CHECK(findings[0].kind == Kind::AgainstNormals);
    CHECK(findings[0].to_flip.empty());
    auto right = scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nusemtl grey\ng sheet\n"
                                "f 1//1 2//1 3//1\n");
    CHECK(rad::check_orientation(right).empty());
}

TEST_CASE("--flip reverses named groups and names the known ones for a typo") {
    int count = 0;
    const auto first = cube(0, 0, 0, "box", {}, true, &count);
    auto scene = scene_from_obj("usemtl grey\n" + first + cube(3, 0, 0, "fine", {}, false, &count));
    const auto flipped = rad::flip_groups(scene, {"box"});
    REQUIRE(flipped.size() == 1);
    CHECK(flipped[0].faces == 6);
    CHECK(flipped[0].what == "group");
    CHECK(rad::check_orientation(scene).empty());
    CHECK_THROWS_WITH(rad::flip_groups(scene, {"bx"}), Catch::Contains("no group 'bx'") &&
                                                           Catch::Contains("box, fine") &&
                                                           Catch::Contains("materials: grey"));
}

TEST_CASE("--flip takes a material's name where no group has it (a file without groups)") {
    int count = 0;
    const auto lamp = cube(0, 0, 0, "", {}, true, &count); // inside out
    const auto grey = cube(3, 0, 0, "", {}, false, &count);
    auto scene = scene_from_obj("usemtl lamp\n" + lamp + "usemtl grey\n" + grey);
    REQUIRE(!rad::check_orientation(scene).empty());
    const auto flipped = rad::flip_groups(scene, {"lamp"});
    REQUIRE(flipped.size() == 1);
    CHECK(flipped[0].what == "material");
    CHECK(flipped[0].faces == 6);
    CHECK(rad::check_orientation(scene).empty());
}

TEST_CASE("the project's scenes give no orientation finding") {
    for (const char* name : {"cornell", "goral", "room1", "room2"}) {
        CAPTURE(name);
        const auto scene = rad::load_obj(std::string(RADIOSITY_SOURCE_DIR) + "/scenes/" + name +
                                         "/" + name + ".obj");
        for (const auto& f : rad::check_orientation(scene)) FAIL(rad::describe(f, scene));
    }
}

TEST_CASE("a closed room facing outward around an object is found and turned inward") {
    int count = 0;
    std::string obj = "usemtl grey\n" + cube(-1, -1, -1, "room", {}, false, &count);
    // Scale the room to 4 x 4 x 4 around a unit cube.
    auto scene = scene_from_obj(scaled(obj, 4, 2) + cube(0, 0, 0, "box", {}, false, &count));
    const auto findings = rad::check_orientation(scene);
    REQUIRE(findings.size() == 1);
    CHECK(findings[0].kind == Kind::RoomOutward);
    CHECK(scene.groups[findings[0].group] == "room");
    CHECK(findings[0].to_flip.size() == 6);
    CHECK_THAT(rad::describe(findings[0], scene), Catch::Contains("face out of their room"));
    rad::fix_orientation(scene, findings);
    CHECK(rad::check_orientation(scene).empty());
    // Alone in its scene, a closed surface may be an empty room or an object: no opinion.
    CHECK(rad::check_orientation(scene_from_obj(obj)).empty());
}

TEST_CASE("visibility voting turns a room modelled as seen from outside, and nothing else") {
    // The project's Cornell box with every face of the room (floor, ceiling, light, walls)
    // reversed: the walls are separate open pieces, so topology has nothing to say.
    const std::string path = std::string(RADIOSITY_SOURCE_DIR) + "/scenes/cornell/cornell.obj";
    auto scene = rad::load_obj(path);
    std::vector<std::string> room_groups{"floor", "ceiling", "light", "back", "right", "left"};
    for (const auto& g : room_groups) (void)rad::flip_groups(scene, {g});
    CHECK(rad::check_orientation(scene).empty());
    const auto facing = rad::check_facing_by_visibility(scene);
    std::vector<std::string> found;
    for (const auto& f : facing) {
        CHECK(f.kind == Kind::FacingAway);
        found.push_back(scene.groups[f.group]);
    }
    std::sort(found.begin(), found.end());
    std::sort(room_groups.begin(), room_groups.end());
    CHECK(found == room_groups);
    rad::fix_orientation(scene, facing);
    CHECK(rad::check_facing_by_visibility(scene).empty());
    // The result is the original file's orientation, face by face.
    const auto original = rad::load_obj(path);
    REQUIRE(original.polygons.size() == scene.polygons.size());
    for (std::size_t f = 0; f < scene.polygons.size(); ++f)
        CHECK(scene.polygons[f].vertices == original.polygons[f].vertices);
}

TEST_CASE("visibility voting stays silent on right scenes, a lamp under its ceiling included") {
    const std::string src = RADIOSITY_SOURCE_DIR;
    for (const auto& path : {src + "/scenes/cornell/cornell.obj", src + "/scenes/goral/goral.obj",
                             src + "/scenes/room1/room1.obj", src + "/scenes/room2/room2.obj",
                             src + "/tests/data/cornell-original/CornellBox-Original.obj",
                             src + "/tests/data/embree-cornell/cornell_box.obj"}) {
        CAPTURE(path);
        auto scene = rad::load_obj(path);
        rad::remove_duplicate_faces(scene);
        rad::fix_orientation(scene, rad::check_orientation(scene));
        for (const auto& f : rad::check_facing_by_visibility(scene)) FAIL(rad::describe(f, scene));
    }
}

TEST_CASE("faces written twice are dropped and reported; a face and its reverse are kept") {
    // A square, the same square from another corner, and its reverse (the other side).
    auto scene = scene_from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nusemtl grey\n"
                                "f 1 2 3 4\nf 3 4 1 5\nf 4 3 2 1\n");
    const auto report = rad::remove_duplicate_faces(scene);
    CHECK(report.removed == 1);
    CHECK(report.first_line == 9);
    CHECK(report.first_original_line == 8);
    REQUIRE(scene.polygons.size() == 2);
    CHECK(scene.polygons[1].line == 10);

    // McGuire's CornellBox-Original: each box's "Bottom Face" repeats one of its sides.
    auto cornell = rad::load_obj(std::string(RADIOSITY_SOURCE_DIR) +
                                 "/tests/data/cornell-original/CornellBox-Original.obj");
    const auto found = rad::remove_duplicate_faces(cornell);
    CHECK(found.removed == 2);
    CHECK(found.first_line == 107);
    CHECK(found.first_original_line == 93);
    CHECK(rad::check_orientation(cornell).size() == 0);
}
