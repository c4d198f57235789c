// Contact imprinting: near-coincident contacts, conformity across shared edges, what is
// left alone.
#include "helpers.hpp"

#include <catch2/catch.hpp>

#include "mesh/imprint/box_pairs.hpp"

#include <map>
#include <random>
#include <set>

using namespace testing_helpers;

namespace {
// A 2 x 2 floor as two 1 x 2 quads sharing an edge at x = 0, and a 0.5 box (five faces,
// outward) standing across that edge at height `lift` (negative: sunk into the floor).
std::string floor_and_box(double lift, double box_x = 0) {
    auto num = [](double v) { return std::to_string(v); };
    std::string s = "v -1 0 -1\nv -1 0 1\nv 0 0 1\nv 0 0 -1\nv 1 0 1\nv 1 0 -1\n"
                    "g floor\nusemtl grey\nf 1 2 3 4\nf 4 3 5 6\n";
    const double x0 = box_x - 0.25, x1 = box_x + 0.25, y0 = lift, y1 = lift + 0.5;
    for (double y : {y0, y1})
        s += "v " + num(x0) + " " + num(y) + " -0.25\nv " + num(x1) + " " + num(y) + " -0.25\nv " +
             num(x1) + " " + num(y) + " 0.25\nv " + num(x0) + " " + num(y) + " 0.25\n";
    // Vertices 7..10 at the bottom, 11..14 at the top; faces wound outward.
    s += "g box\nf 11 12 8 7\nf 12 13 9 8\nf 13 14 10 9\nf 14 11 7 10\nf 14 13 12 11\n";
    return s;
}

radfmt::MeshData meshed(const std::string& obj, rad::ImprintReport* report = nullptr,
                        double max_edge = 0.1, double gap = rad::kContactGap) {
    auto scene = scene_from_obj(obj, kGreyMtl, "imprint");
    const auto r = rad::imprint_contacts(scene, 1e-7, {}, gap);
    if (report) *report = r;
    rad::SubdivisionOptions options;
    options.max_edge = max_edge;
    return rad::subdivide(scene, options);
}

double group_area(const radfmt::MeshData& mesh, const std::string& group) {
    double a = 0;
    for (const auto& p : mesh.patches)
        if (mesh.groups[p.group] == group) a += p.area;
    return a;
}

// Length of the edges of a group's patches that no other patch of the group shares: its
// outline, plus both sides of any crack or T-vertex.
double open_length(const radfmt::MeshData& mesh, const std::string& group) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
    for (const auto& p : mesh.patches) {
        if (mesh.groups[p.group] != group) continue;
        for (int k = 0; k < p.corner_count(); ++k) {
            auto a = p.corners[k], b = p.corners[(k + 1) % p.corner_count()];
            ++count[{std::min(a, b), std::max(a, b)}];
        }
    }
    double length = 0;
    for (const auto& [edge, n] : count)
        if (n == 1)
            length +=
                rad::length(rad::operator-(mesh.vertices[edge.first], mesh.vertices[edge.second]));
    return length;
}

double smallest_area(const radfmt::MeshData& mesh) {
    double a = 1e300;
    for (const auto& p : mesh.patches) a = std::min(a, p.area);
    return a;
}
} // namespace

TEST_CASE("a box on a floor: its footprint is removed, across the floor's shared edge") {
    rad::ImprintReport report;
    const auto mesh = meshed(floor_and_box(0), &report);
    CHECK(report.faces_imprinted == 2);
    CHECK(report.regions_removed == 2); // half the footprint in each floor quad
    CHECK(report.area_removed == Approx(0.25).epsilon(1e-12));
    CHECK(group_area(mesh, "floor") == Approx(4 - 0.25).epsilon(1e-12));
    // Conforming: the open edges are the outline (8) and the footprint (2), nothing else.
    CHECK(open_length(mesh, "floor") == Approx(8 + 2).epsilon(1e-9));
    for (const auto& p : mesh.patches)
        if (mesh.groups[p.group] == "floor")
            CHECK_FALSE((std::abs(p.centroid[0]) < 0.25 && std::abs(p.centroid[2]) < 0.25));
}

TEST_CASE("near-coincident contacts are contacts, without slivers or cracks") {
    const double regular = smallest_area(meshed(floor_and_box(0)));
    // A gap or an overlap far below the tolerance (1e-7 of the scene's size).
    for (double lift : {1e-10, -1e-10, 3e-9, -3e-9}) {
        INFO("lift " << lift);
        rad::ImprintReport report;
        const auto mesh = meshed(floor_and_box(lift), &report);
        CHECK(report.regions_removed == 2);
        CHECK(group_area(mesh, "floor") == Approx(4 - 0.25).epsilon(1e-7));
        CHECK(open_length(mesh, "floor") == Approx(10).epsilon(1e-7));
        CHECK(smallest_area(mesh) > 0.5 * regular);
    }
    // Its side a hair from the floor's shared edge: snapped onto it, no thin strip.
    const auto flush = meshed(floor_and_box(0, 0.25 + 1e-10));
    CHECK(smallest_area(flush) > 0.5 * regular);
    CHECK(group_area(flush, "floor") == Approx(4 - 0.25).epsilon(1e-7));
}

TEST_CASE("what does not touch, or belongs to the same object, is left whole") {
    rad::ImprintReport report;
    // A box 2 cm above the floor does not touch it (the scene's size is 2.87; the contact
    // gap 2e-3 of that is 5.7 mm); nor does one 1 mm above, with no contact gap.
    for (const auto& [lift, gap] : {std::pair{0.02, rad::kContactGap}, std::pair{1e-3, 0.0}}) {
        INFO("lift " << lift << ", gap " << gap);
        const auto floating = meshed(floor_and_box(lift), &report, 0.1, gap);
        CHECK(report.faces_imprinted == 0);
        CHECK(group_area(floating, "floor") == Approx(4).epsilon(1e-12));
    }
    // A closed room's walls meet along shared edges: nothing to imprint.
    meshed(cube_obj(1), &report);
    CHECK(report.faces_imprinted == 0);
}

TEST_CASE("a box 1 mm above the floor, within the contact gap, imprints it as if standing on it") {
    rad::ImprintReport report;
    const auto mesh = meshed(floor_and_box(1e-3), &report);
    CHECK(report.faces_imprinted == 2);
    CHECK(report.regions_removed == 2); // the floor under it sees the box's inside
    CHECK(group_area(mesh, "floor") == Approx(4 - 0.25).epsilon(1e-12));
    CHECK(open_length(mesh, "floor") == Approx(8 + 2).epsilon(1e-9));
}

TEST_CASE("a contact a hair over a face's edge removes nothing there, and keeps grids") {
    const double regular = smallest_area(meshed(floor_and_box(0)));
    for (double shift : {-1e-10, 1e-10}) {
        INFO("shift " << shift);
        rad::ImprintReport report;
        // The box stands on the right floor quad, overlapping the left one by 1e-10 or not.
        const auto mesh = meshed(floor_and_box(0, 0.25 + shift), &report);
        CHECK(report.regions_removed == 1); // its footprint, from the right quad only
        CHECK(report.area_removed == Approx(0.25).epsilon(1e-7));
        // The lines run on across the left quad: rectangles there too, no thin pieces, and
        // the floor stays conforming (open edges: its outline and the footprint).
        CHECK(smallest_area(mesh) > 0.5 * regular);
        CHECK(open_length(mesh, "floor") == Approx(10).epsilon(1e-7));
        for (const auto& p : mesh.patches) CHECK(p.corner_count() == 4);
    }
}

// The broad phase of contact finding against every pair tried: flat boxes sharing an extent
// (a finely triangulated floor and wall), boxes larger than many cells, empty boxes, and
// boxes that only touch, which count.
TEST_CASE("for_each_overlapping_pair finds exactly the overlapping pairs", "[imprint]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<rad::Box> boxes;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) { // floor tiles at y = 0, sharing edges
            rad::Box b;
            b.add({i * 0.1, 0, j * 0.1});
            b.add({(i + 1) * 0.1, 0, (j + 1) * 0.1});
            boxes.push_back(b);
        }
    for (int k = 0; k < 600; ++k) { // small boxes anywhere, some flat
        rad::Box b;
        const radfmt::Vec3 p{4 * unit(rng), unit(rng) < 0.2 ? 0.0 : unit(rng), 4 * unit(rng)};
        b.add(p);
        b.add(rad::operator+(p, radfmt::Vec3{0.2 * unit(rng), 0.2 * unit(rng), 0.2 * unit(rng)}));
        boxes.push_back(b);
    }
    for (int k = 0; k < 5; ++k) { // large ones: a wall, slabs
        rad::Box b;
        b.add({0, 0, 0.7 * k});
        b.add({4, 1, 0.7 * k + (k % 2 ? 0.0 : 0.5)});
        boxes.push_back(b);
    }
    boxes.push_back(rad::Box{}); // empty: no pairs
    std::set<std::pair<std::uint32_t, std::uint32_t>> found, expected;
    rad::for_each_overlapping_pair(boxes, [&](std::uint32_t a, std::uint32_t b) {
        REQUIRE(a < b);
        REQUIRE(found.insert({a, b}).second); // once each
    });
    auto overlap = [](const rad::Box& a, const rad::Box& b) {
        for (int k = 0; k < 3; ++k)
            if (a.lo[k] > b.hi[k] || b.lo[k] > a.hi[k]) return false;
        return true;
    };
    for (std::uint32_t a = 0; a < boxes.size(); ++a)
        for (std::uint32_t b = a + 1; b < boxes.size(); ++b)
            if (overlap(boxes[a], boxes[b])) expected.insert({a, b});
    CHECK(expected.size() > 5000);
    CHECK(found == expected);

    // Grouped (every other row of floor tiles a group, the rest in none): the same pairs but
    // those of one group.
    std::vector<std::uint32_t> groups(boxes.size(), rad::kNoGroup);
    for (std::uint32_t b = 0; b < 1600; ++b)
        if ((b / 40) % 2 == 0) groups[b] = b / 40;
    std::set<std::pair<std::uint32_t, std::uint32_t>> found_grouped, expected_grouped;
    rad::for_each_overlapping_pair(
        boxes,
        [&](std::uint32_t a, std::uint32_t b) {
            REQUIRE(a < b);
            REQUIRE(found_grouped.insert({a, b}).second);
        },
        groups);
    for (const auto& [a, b] : expected)
        if (groups[a] == rad::kNoGroup || groups[a] != groups[b]) expected_grouped.insert({a, b});
    CHECK(expected_grouped.size() < expected.size() - 500);
    CHECK(found_grouped == expected_grouped);
}
