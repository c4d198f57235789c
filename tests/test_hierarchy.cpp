// Hierarchical form factors (rad-ff --method hierarchical) and the solve over their links,
// against closed forms, a furnace, reciprocity, the analytic matrix and themselves.
#include "helpers.hpp"
#include "hierarchy/direct_light.hpp"
#include "hierarchy/node_geometry.hpp"
#include "hierarchy/surfaces.hpp"
#include "radfmt/container.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/hierarchy.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/random.hpp"
#include "radiosity/solver.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <span>

using namespace testing_helpers;
using Catch::Matchers::Contains;

namespace {
// Two unit squares facing each other: the first at z = 0 (normal +z), the second at `gap`
// above (normal -z) or, with `perpendicular`, standing on the first's edge x = 1 (normal -x).
radfmt::MeshData two_squares(bool perpendicular, double gap, double max_edge) {
    std::string obj;
    int count = 0;
    append_obj_face(obj, count, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, "grey", "floor");
    if (perpendicular)
        append_obj_face(obj, count, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}, "grey", "wall");
    else
        append_obj_face(obj, count, {{0, 0, gap}, {0, 1, gap}, {1, 1, gap}, {1, 0, gap}}, "grey",
                        "ceiling");
    return mesh_from_obj(obj, max_edge);
}

// The mean row sum of the patches of `group`: their form factor to everything else.
double group_form_factor(const radfmt::MeshData& mesh, const radfmt::LinkData& links,
                         const std::string& group) {
    const auto sums = rad::link_row_sums(mesh, links);
    double weighted = 0, area = 0;
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        if (mesh.groups[mesh.patches[p].group] == group) {
            weighted += mesh.patches[p].area * sums[p];
            area += mesh.patches[p].area;
        }
    return weighted / area;
}

rad::Channels solve(const radfmt::MeshData& mesh, const rad::TransportOperator& op,
                    const rad::Channels& emission, const std::string& method = "gs") {
    rad::SolveControl control;
    control.max_iterations = 500;
    control.tolerance = 1e-10;
    (void)mesh;
    return rad::solver(method).solve(op, emission, control).radiosity;
}

// The analytic matrix of `mesh` and its solution for `emission`.
std::pair<radfmt::FormFactorData, rad::Channels> analytic_solution(const radfmt::MeshData& mesh,
                                                                   const rad::Channels& emission) {
    rad::FormFactorOptions analytic;
    analytic.method = "analytic";
    auto ff = rad::compute_form_factors(mesh, rad::resolve_form_factor_options(analytic));
    auto b = solve(mesh, rad::make_operator(mesh, ff), emission);
    return {std::move(ff), std::move(b)};
}
// ... for the mesh's own emission.
std::pair<radfmt::FormFactorData, rad::Channels> analytic_solution(const radfmt::MeshData& mesh) {
    return analytic_solution(mesh, rad::emission_of(mesh));
}

// Patch-to-patch F from links: each link's share into each part of its receiver (over the
// part's share of the area), from each part of its source (spread over the part by area).
std::map<std::pair<std::uint32_t, std::uint32_t>, double> expand(const radfmt::MeshData& mesh,
                                                                 const radfmt::LinkData& links) {
    const auto area = rad::link_node_areas(mesh, links);
    std::map<std::pair<std::uint32_t, std::uint32_t>, double> f;
    for (std::size_t r = 0; r < links.nodes.size(); ++r)
        for (auto l = links.link_start[r]; l < links.link_start[r + 1]; ++l) {
            const auto into = radfmt::share_slots(links, r);
            const auto from = radfmt::share_slots(links, links.source[l]);
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) {
                    if (links.receiver_share[l][i] == 0 || links.source_share[l][j] == 0) continue;
                    const auto& receiver = links.nodes[into[i]];
                    const auto& source = links.nodes[from[j]];
                    const double g =
                        rad::delivered_factor(links.factor[l], links.receiver_share[l][i], area[r],
                                              area[into[i]]) *
                        links.source_share[l][j] / radfmt::kShareTotal;
                    for (auto a = receiver.first; a < receiver.first + receiver.count; ++a)
                        for (auto b = source.first; b < source.first + source.count; ++b) {
                            const auto q = links.leaf_order[b];
                            f[{links.leaf_order[a], q}] += g * mesh.patches[q].area / area[from[j]];
                        }
                }
        }
    return f;
}

// The links with every share by area: what a link did when it carried one number.
radfmt::LinkData shares_by_area(const radfmt::MeshData& mesh, radfmt::LinkData links) {
    const auto area = rad::link_node_areas(mesh, links);
    auto by_area = [&](std::size_t node) {
        const auto slots = radfmt::share_slots(links, node);
        radfmt::LinkShares out{};
        int sum = 0;
        for (int k = 0; k < 4; ++k)
            if (slots[k] != radfmt::kNoNode) {
                out[k] =
                    std::uint16_t(std::lround(area[slots[k]] / area[node] * radfmt::kShareTotal));
                sum += out[k];
            }
        out[0] = std::uint16_t(int(out[0]) + int(radfmt::kShareTotal) - sum);
        return out;
    };
    for (std::size_t r = 0; r < links.nodes.size(); ++r)
        for (auto l = links.link_start[r]; l < links.link_start[r + 1]; ++l) {
            links.receiver_share[l] = by_area(r);
            links.source_share[l] = by_area(links.source[l]);
        }
    return links;
}

// Per-patch rms of b against reference (relative, area-weighted) and the worst group's mean
// off the reference's, emitters left out.
std::pair<double, double> distance(const radfmt::MeshData& mesh, const rad::Channels& b,
                                   const rad::Channels& reference) {
    double se = 0, sr = 0;
    std::map<std::uint32_t, std::pair<double, double>> group;
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        if (mesh.materials[mesh.patches[p].material].emits()) continue;
        const double area = mesh.patches[p].area;
        for (std::size_t c = 0; c < 3; ++c) {
            se += area * std::pow(b.at(p, c) - reference.at(p, c), 2);
            sr += area * std::pow(reference.at(p, c), 2);
            group[mesh.patches[p].group].first += area * b.at(p, c);
            group[mesh.patches[p].group].second += area * reference.at(p, c);
        }
    }
    double worst = 0;
    for (const auto& [g, sums] : group)
        worst = std::max(worst, std::abs(sums.first / sums.second - 1));
    return {std::sqrt(se / sr), worst};
}
} // namespace

TEST_CASE("hierarchical: parallel and perpendicular squares match Howell's closed forms") {
    // 16 x 16 patches a square: links join blocks of them, the sum must still be the whole.
    const auto parallel = two_squares(false, 1.0, 1.0 / 16);
    const auto links = rad::compute_links(parallel, {});
    // The matrix has 2 x 256 x 256 non-zeros.
    CHECK(links.links() < 2 * 256 * 256 / 5);
    CHECK(group_form_factor(parallel, links, "floor") ==
          Approx(rad::parallel_rectangles_form_factor(1, 1, 1)).epsilon(0.01));

    const auto perpendicular = two_squares(true, 0, 1.0 / 16);
    const auto links_p = rad::compute_links(perpendicular, {});
    CHECK(group_form_factor(perpendicular, links_p, "floor") ==
          Approx(rad::perpendicular_rectangles_form_factor(1, 1, 1)).epsilon(0.01));
}

TEST_CASE("hierarchical: a polygon patch, not convex, is the surface it covers") {
    // An L (the 2 x 2 square without its quadrant [1, 2]^2) under a 2 x 2 square: each
    // quadrant sees the square as the whole does, so F(L -> top) = f, F(top -> L) = 3f/4.
    const double f = rad::parallel_rectangles_form_factor(2, 2, 1);
    const auto ell = polygon_under_square({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 3,
                                          {5.0 / 6, 5.0 / 6, 0});
    const auto sums = rad::link_row_sums(ell, rad::compute_links(ell, {}));
    CHECK(sums[0] == Approx(f).epsilon(0.01));
    CHECK(sums[1] == Approx(0.75 * f).epsilon(0.01));
}

TEST_CASE("hierarchical: a closed box is a furnace, B = E / (1 - rho) everywhere") {
    const auto mesh = mesh_from_obj(cube_obj(), 1.0 / 8); // 384 patches
    rad::HierarchyOptions options;
    options.epsilon = 3e-3; // finer than the default: row sums within a few percent
    const auto links = rad::compute_links(mesh, options);
    const auto sums = rad::link_row_sums(mesh, links);
    double mean = 0;
    // Per patch within the sampling of its cluster links (64 pairs each), on average exact.
    for (double s : sums) {
        CHECK(s == Approx(1).margin(0.06));
        mean += s / double(sums.size());
    }
    CHECK(mean == Approx(1).margin(0.01));
    const auto op = rad::make_operator(mesh, links); // grey: rho 0.5
    rad::Channels emission(mesh.patches.size(), 3);
    for (auto& e : emission.values) e = 1;
    for (const char* method : {"gs", "jacobi"}) {
        const auto b = solve(mesh, op, emission, method);
        for (double value : b.values) CHECK(value == Approx(2).epsilon(0.06));
    }
}

TEST_CASE("hierarchical: links are reciprocal, patch to patch") {
    const auto mesh = mesh_from_obj(cube_obj(), 1.0 / 6);
    rad::HierarchyOptions options;
    options.epsilon = 3e-3;
    const auto links = rad::compute_links(mesh, options);
    const auto f = expand(mesh, links);
    double total = 0, asymmetry = 0;
    for (const auto& [pq, value] : f) {
        const auto [p, q] = pq;
        const auto back = f.find({q, p});
        const double a = mesh.patches[p].area * value;
        const double b = back == f.end() ? 0.0 : mesh.patches[q].area * back->second;
        total += a;
        asymmetry += std::abs(a - b);
    }
    // Exact where both directions were linked at one pair of nodes; where only one side was
    // split further, the two estimates differ by their sampling.
    CHECK(asymmetry / total < 0.05);
}

TEST_CASE("hierarchical: converges to the analytic solution as epsilon shrinks", "[slow]") {
    const auto mesh = cornell_mesh(0.05);
    const auto [ff, reference] = analytic_solution(mesh);
    const auto emission = rad::emission_of(mesh);
    std::vector<double> errors;
    std::vector<std::uint64_t> link_counts;
    for (double epsilon : {3e-2, 1e-2, 1e-3}) {
        rad::HierarchyOptions options;
        options.epsilon = epsilon;
        const auto links = rad::compute_links(mesh, options);
        const auto b = solve(mesh, rad::make_operator(mesh, links), emission);
        double se = 0, sr = 0;
        for (std::size_t i = 0; i < b.values.size(); ++i) {
            const double area = mesh.patches[i / 3].area;
            se += area * std::pow(b.values[i] - reference.values[i], 2);
            sr += area * std::pow(reference.values[i], 2);
        }
        errors.push_back(std::sqrt(se / sr));
        link_counts.push_back(links.links());
    }
    INFO("rms errors " << errors[0] << " " << errors[1] << " " << errors[2]);
    CHECK(errors[1] < errors[0]);
    CHECK(errors[2] < errors[1]);
    CHECK(errors[2] < 0.005);
    CHECK(link_counts[0] < link_counts[1]);
    CHECK(link_counts[1] < link_counts[2]);
}

TEST_CASE("hierarchical: a link reaches its receiver's parts and reads its source's by their "
          "share of the transfer") {
    // One number per link spreads a block's mean over all of it: on the Cornell box the
    // ceiling above the lit floor came out 1% dark and the per-patch rms 5% at 1/100 of the
    // analytic matrix's non-zeros (bench/hierarchical). Parts two levels down carry their own.
    const auto mesh = cornell_mesh(0.03);
    const auto [ff, reference] = analytic_solution(mesh);
    const auto emission = rad::emission_of(mesh);
    rad::HierarchyOptions options;
    options.epsilon = 3e-2;
    const auto links = rad::compute_links(mesh, options);
    REQUIRE(links.links() * 20 < ff.nonzeros());
    const auto flat = shares_by_area(mesh, links);
    const auto [rms, worst] =
        distance(mesh, solve(mesh, rad::make_operator(mesh, links), emission), reference);
    const auto [rms_flat, worst_flat] =
        distance(mesh, solve(mesh, rad::make_operator(mesh, flat), emission), reference);
    INFO("rms " << rms << " (by area " << rms_flat << "), worst surface " << worst << " ("
                << worst_flat << ")");
    CHECK(rms < 0.6 * rms_flat);
    CHECK(worst < 0.6 * worst_flat);
    // Shares move light within a node; they never add or lose any.
    const auto sums = rad::link_row_sums(mesh, links);
    const auto flat_sums = rad::link_row_sums(mesh, flat);
    double total = 0, flat_total = 0;
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        total += mesh.patches[p].area * sums[p];
        flat_total += mesh.patches[p].area * flat_sums[p];
    }
    CHECK(total == Approx(flat_total).epsilon(1e-4));
}

TEST_CASE("hierarchical: the oracle's direct light is the lamp's form factor where it is seen, "
          "none in a full shadow") {
    // A 2 x 2 floor, a 0.4 x 0.4 lamp 1 above its middle facing down, and a square 0.2 above
    // the floor's corner [0, 0.8]^2 that hides the lamp from the floor where x and y are both
    // under 0.8 - 0.2 (1.2 - 0.8) / 0.8 = 0.7 and lets all of it be seen where either is
    // over 0.8.
    std::string obj;
    int count = 0;
    append_obj_face(obj, count, {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, "grey", "floor");
    append_obj_face(obj, count, {{0.8, 0.8, 1}, {0.8, 1.2, 1}, {1.2, 1.2, 1}, {1.2, 0.8, 1}},
                    "lamp", "lamp");
    append_obj_face(obj, count, {{0, 0, 0.2}, {0.8, 0, 0.2}, {0.8, 0.8, 0.2}, {0, 0.8, 0.2}},
                    "grey", "shelf");
    const auto mesh = mesh_from_obj(obj, 0.1);
    const rad::RayScene scene(mesh);
    const rad::FormFactorContext context(mesh, scene);
    const auto surface = rad::hierarchy::connected_surfaces(mesh);
    const auto tree = rad::hierarchy::build_surface_tree(mesh, surface);
    std::vector<bool> emitter;
    for (const auto& m : mesh.materials) emitter.push_back(m.emits());
    const rad::hierarchy::NodeGeometries geometry(mesh, context.polygons, tree, emitter, surface);
    const auto light = rad::hierarchy::estimate_direct_light(mesh, tree, geometry, scene, 1);
    REQUIRE(!light.empty());
    const std::vector<rad::Vec3> lamp = {
        {0.8, 0.8, 1}, {0.8, 1.2, 1}, {1.2, 1.2, 1}, {1.2, 0.8, 1}};
    int lit = 0, shadowed = 0;
    std::uint32_t floor_node = radfmt::kNoNode;
    for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
        if (geometry[i].one_surface && geometry[i].planar && geometry[i].normal[2] > 0.5 &&
            std::abs(geometry[i].area - 4) < 1e-9)
            floor_node = i;
        if (!tree.is_leaf(i)) continue;
        const auto& patch = mesh.patches[tree.leaf_order[tree.nodes[i].first]];
        if (mesh.groups[patch.group] != "floor") continue;
        CHECK(light.spread[i] == 0); // one patch: nothing varies inside its one part
        const double x = patch.centroid[0], y = patch.centroid[1];
        if (x > 0.85 || y > 0.85) {
            INFO("floor patch at " << x << ", " << y);
            const double exact =
                rad::point_to_polygon_form_factor(patch.centroid, patch.normal, lamp);
            CHECK(light.mean[i] == Approx(exact).epsilon(0.03));
            ++lit;
        } else if (x < 0.65 && y < 0.65) {
            CHECK(light.mean[i] == 0);
            ++shadowed;
        }
    }
    CHECK(lit > 250);
    CHECK(shadowed > 20);
    // The floor, lit in its middle and dark in its corner, varies inside its parts.
    REQUIRE(floor_node != radfmt::kNoNode);
    CHECK(light.spread[floor_node] > 0.2 * light.mean[floor_node]);
}

TEST_CASE("hierarchical: light that varies inside a source's parts is linked finer") {
    // The ceiling sees most of the floor's middle, where the lamp lights it most: a link from
    // the whole floor that reads the mean of each of its quarters undercounts what the
    // ceiling's middle gets. Without the refinement for it, at this size: the ceiling 0.54%
    // dark, the worst surface 0.59% off, 2.23% rms per patch; with it 0.13%, 0.34% and 1.56%.
    const auto mesh = cornell_mesh(0.04);
    const auto [ff, reference] = analytic_solution(mesh);
    const auto links = rad::compute_links(mesh, {});
    const auto b = solve(mesh, rad::make_operator(mesh, links), rad::emission_of(mesh));
    double got = 0, expected = 0;
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        if (mesh.groups[mesh.patches[p].group] == "ceiling" &&
            !mesh.materials[mesh.patches[p].material].emits())
            for (std::size_t c = 0; c < 3; ++c) {
                got += mesh.patches[p].area * b.at(p, c);
                expected += mesh.patches[p].area * reference.at(p, c);
            }
    const auto [rms, worst] = distance(mesh, b, reference);
    INFO("ceiling " << got / expected << ", worst surface " << worst << ", rms " << rms);
    CHECK(got / expected == Approx(1).margin(0.0025));
    CHECK(worst < 0.004);
    CHECK(rms < 0.018);
}

TEST_CASE("hierarchical: a strip close in front of a large wall sees it, as analytic says") {
    // pandora has such a strip (a bevel 0.5 units off a wall, leaning 14 degrees): the wall's
    // node (not convex, too many patches to integrate one by one) was integrated from 16
    // points of its own, which all missed the part of it near the strip, and the strip was
    // linked to it with F = 0.025 where it is 0.99.
    std::string obj;
    int count = 0;
    // An L-shaped wall at x = 0 facing +x, most of it behind the strip's plane.
    append_obj_face(obj, count, {{0, 0, -8}, {0, 5, -8}, {0, 5, 2.5}, {0, 0, 2.5}}, "grey", "wall");
    append_obj_face(obj, count, {{0, 5, -8}, {0, 10, -8}, {0, 10, -3}, {0, 5, -3}}, "grey", "wall");
    // The strip: 4 long, 0.1 wide, 0.0125 to 0.0375 off the wall, facing it.
    append_obj_face(obj, count,
                    {{0.0125, 1, 2}, {0.0375, 1, 2.1}, {0.0375, 5, 2.1}, {0.0125, 5, 2}}, "grey",
                    "strip");
    const auto mesh = mesh_from_obj(obj, 0.5);
    rad::FormFactorOptions analytic;
    analytic.method = "analytic";
    const auto ff = rad::compute_form_factors(mesh, rad::resolve_form_factor_options(analytic));
    double expected = 0, area = 0;
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        if (mesh.groups[mesh.patches[p].group] == "strip") {
            for (auto k = ff.row_start[p]; k < ff.row_start[p + 1]; ++k)
                expected += mesh.patches[p].area * ff.values[k];
            area += mesh.patches[p].area;
        }
    expected /= area;
    REQUIRE(expected > 0.5);
    const auto links = rad::compute_links(mesh, {});
    CHECK(group_form_factor(mesh, links, "strip") == Approx(expected).epsilon(0.03));
}

TEST_CASE("hierarchical: a link lights one surface, never two apart on one plane") {
    // Two pillars' faces on one plane, of one material, see different things: a link into
    // both would give them one irradiance (pandora's colonnade came out 18% apart).
    std::string obj;
    int count = 0;
    append_obj_face(obj, count, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, "grey", "left");
    append_obj_face(obj, count, {{3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}}, "grey", "right");
    // A small square far above (F about 0.003, well under epsilon) facing down.
    append_obj_face(obj, count, {{2, 0, 10}, {2, 1, 10}, {3, 1, 10}, {3, 0, 10}}, "grey", "top");
    const auto mesh = mesh_from_obj(obj, 0.25);
    const auto links = rad::compute_links(mesh, {});
    REQUIRE(links.links() > 0);
    for (std::size_t r = 0; r < links.nodes.size(); ++r) {
        if (links.link_start[r] == links.link_start[r + 1]) continue;
        std::set<std::string> groups;
        const auto& n = links.nodes[r];
        for (auto k = n.first; k < n.first + n.count; ++k)
            groups.insert(mesh.groups[mesh.patches[links.leaf_order[k]].group]);
        INFO("node " << r << " of " << n.count << " patches receives");
        CHECK(groups.size() == 1);
    }
    // Each face still gets what it sees of the top.
    CHECK(group_form_factor(mesh, links, "left") ==
          Approx(group_form_factor(mesh, links, "right")).epsilon(0.1));
}

TEST_CASE("hierarchical: two groups of small surfaces light each other as groups") {
    // 8 x 8 tiles on the floor and 8 x 8 on the ceiling 1.5 above, each tile a surface of one
    // patch. Refined together, every floor tile came to receive from every ceiling tile one by
    // one (4096 links each way); each direction splitting only its own receivers, a tile
    // receives from a few groups of the other side's tiles.
    std::string obj;
    int count = 0;
    constexpr int kTiles = 8;
    constexpr double kPitch = 0.15, kSide = 0.1, kHeight = 1.5;
    for (int i = 0; i < kTiles; ++i)
        for (int j = 0; j < kTiles; ++j) {
            const double x = i * kPitch, y = j * kPitch;
            append_obj_face(
                obj, count,
                {{x, y, 0}, {x + kSide, y, 0}, {x + kSide, y + kSide, 0}, {x, y + kSide, 0}},
                "grey", "floor");
            append_obj_face(obj, count,
                            {{x, y, kHeight},
                             {x, y + kSide, kHeight},
                             {x + kSide, y + kSide, kHeight},
                             {x + kSide, y, kHeight}},
                            "grey", "ceiling");
        }
    const auto mesh = mesh_from_obj(obj, 0.2);
    REQUIRE(mesh.patches.size() == 2 * kTiles * kTiles);
    const auto links = rad::compute_links(mesh, {});
    std::size_t tile_to_tile = 0;
    for (std::size_t r = 0; r < links.nodes.size(); ++r)
        for (auto l = links.link_start[r]; l < links.link_start[r + 1]; ++l)
            tile_to_tile += links.nodes[r].count == 1 && links.nodes[links.source[l]].count == 1;
    INFO(links.links() << " links, " << tile_to_tile << " from one tile to another");
    CHECK(links.links() < 1500);
    CHECK(tile_to_tile < kTiles * kTiles);

    // The ceiling glowing: each floor tile's radiosity against the analytic solution's.
    rad::Channels emission(mesh.patches.size(), 3);
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        if (mesh.groups[mesh.patches[p].group] == "ceiling")
            for (int c = 0; c < 3; ++c) emission.at(p, c) = 1;
    const auto reference = analytic_solution(mesh, emission).second;
    const auto b = solve(mesh, rad::make_operator(mesh, links), emission);
    double worst = 0;
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        if (mesh.groups[mesh.patches[p].group] == "floor")
            worst = std::max(worst, std::abs(b.at(p, 0) / reference.at(p, 0) - 1));
    INFO("worst floor tile off analytic by " << worst);
    CHECK(worst < 0.02);
}

TEST_CASE("hierarchical: light groups superpose, and any thread count gives the same links") {
    const auto mesh = cornell_mesh(0.1);
    radfmt::LinkData one, two;
    {
        rad::ThreadLimit limit(1);
        one = rad::compute_links(mesh, {});
    }
    {
        rad::ThreadLimit limit(2);
        two = rad::compute_links(mesh, {});
    }
    CHECK(one.leaf_order == two.leaf_order);
    CHECK(one.link_start == two.link_start);
    CHECK(one.source == two.source);
    CHECK(one.factor == two.factor);

    // Two halves of the emission solved as 6 channels, against their sum as 3.
    const auto op = rad::make_operator(mesh, one);
    const auto emission = rad::emission_of(mesh);
    rad::Channels halves(mesh.patches.size(), 6);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            halves.at(i, c) = 0.25 * emission.at(i, c);
            halves.at(i, 3 + c) = 0.75 * emission.at(i, c);
        }
    const auto together = solve(mesh, op, emission);
    const auto apart = solve(mesh, op, halves);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        for (int c = 0; c < 3; ++c)
            CHECK(apart.at(i, c) + apart.at(i, 3 + c) ==
                  Approx(together.at(i, c)).epsilon(1e-6).margin(1e-12));
}

TEST_CASE("links files: written and read back whole; a broken tree is refused") {
    const auto mesh = mesh_from_obj(cube_obj(), 0.5);
    const auto links = rad::compute_links(mesh, {});
    const auto dir = temp_dir("links");
    radfmt::Header header;
    radfmt::write_links(dir / "a.links", header, links);
    const auto back = radfmt::read_links(dir / "a.links");
    CHECK(back.leaf_order == links.leaf_order);
    CHECK(back.link_start == links.link_start);
    CHECK(back.source == links.source);
    CHECK(back.factor == links.factor);
    CHECK(back.nodes == links.nodes);
    CHECK(back.receiver_share == links.receiver_share);
    CHECK(back.source_share == links.source_share);

    auto broken = links;
    broken.nodes[0].left = 0; // a node its own child
    radfmt::write_links(dir / "b.links", header, broken);
    CHECK_THROWS_WITH(radfmt::read_links(dir / "b.links"), Contains("out of order"));
    broken = links;
    broken.source[0] = static_cast<std::uint32_t>(links.nodes.size());
    radfmt::write_links(dir / "c.links", header, broken);
    CHECK_THROWS_WITH(radfmt::read_links(dir / "c.links"), Contains("a node that does not exist"));
    broken = links;
    broken.leaf_order[1] = broken.leaf_order[0];
    radfmt::write_links(dir / "d.links", header, broken);
    CHECK_THROWS_WITH(radfmt::read_links(dir / "d.links"), Contains("permutation"));
    broken = links;
    broken.source_share[0][0] += 1;
    radfmt::write_links(dir / "e.links", header, broken);
    CHECK_THROWS_WITH(radfmt::read_links(dir / "e.links"), Contains("do not sum to 65535"));
    broken = links;
    const auto leaf_link = std::find_if(broken.source.begin(), broken.source.end(),
                                        [&](std::uint32_t s) { return broken.is_leaf(s); });
    REQUIRE(leaf_link != broken.source.end());
    auto& shares = broken.source_share[leaf_link - broken.source.begin()];
    shares[0] -= 1;
    shares[3] += 1;
    radfmt::write_links(dir / "f.links", header, broken);
    CHECK_THROWS_WITH(radfmt::read_links(dir / "f.links"),
                      Contains("a part its node does not have"));
    // A leaf that gathers from itself (#55), and a node from its own parent.
    broken = links;
    bool spoiled = false;
    for (std::size_t i = 0; i < broken.nodes.size() && !spoiled; ++i)
        for (auto l = broken.link_start[i]; l < broken.link_start[i + 1] && !spoiled; ++l)
            if (broken.is_leaf(i) && broken.is_leaf(broken.source[l])) {
                broken.source[l] = static_cast<std::uint32_t>(i);
                spoiled = true;
            }
    REQUIRE(spoiled);
    radfmt::write_links(dir / "g.links", header, broken);
    CHECK_THROWS_WITH(radfmt::read_links(dir / "g.links"),
                      Contains("which shares its patches (a patch would light itself)"));
    fs::remove_all(dir);
}

TEST_CASE("hierarchical: a node's points fall on its patches by area, each on the patch the "
          "area table picks") {
    using rad::operator+, rad::operator-;
    // Patches of unequal area and shape, one a face (max_edge beyond every face): a floor of
    // four quads of different sizes, a triangle, a quad facing down, and a hexagon added as a
    // polygon patch, so point() picks among quads, a triangle and a polygon's fan, and each
    // point's normal is its own patch's.
    std::string obj;
    int count = 0;
    for (const auto& [x0, x1, y1] :
         {std::array<double, 3>{0, 0.3, 1}, {0.3, 1, 1}, {1, 1.2, 0.4}, {1.2, 2, 0.4}})
        append_obj_face(obj, count, {{x0, 0, 0}, {x1, 0, 0}, {x1, y1, 0}, {x0, y1, 0}}, "grey",
                        "floor");
    append_obj_face(obj, count, {{2, 2, 0}, {3, 2, 0}, {2, 2.5, 0}}, "grey", "triangle");
    append_obj_face(obj, count, {{0, 3, 0}, {0, 4, 0}, {1.5, 4, 0}, {1.5, 3, 0}}, "grey",
                    "ceiling"); // facing down
    auto mesh = mesh_from_obj(obj, 10);
    // A hexagon: a rectangle 1 x 1.6 and two triangles of base 1.6 and height 0.6.
    add_polygon_patch(
        mesh, {{4, 0, 0}, {5, 0, 0}, {5.6, 0.8, 0}, {5, 1.6, 0}, {4, 1.6, 0}, {3.4, 0.8, 0}}, 2.56,
        {4.5, 0.8, 0}, {0, 0, 1}, mesh.patches.front().material);
    const rad::RayScene scene(mesh);
    const rad::FormFactorContext context(mesh, scene);
    const auto surface = rad::hierarchy::connected_surfaces(mesh);
    const auto tree = rad::hierarchy::build_surface_tree(mesh, surface);
    const std::vector<bool> emitter(mesh.materials.size(), false);
    const rad::hierarchy::NodeGeometries geometry(mesh, context.polygons, tree, emitter, surface);
    REQUIRE(std::any_of(context.polygons.begin(), context.polygons.end(),
                        [](const rad::PatchPolygon& g) { return g.is_polygon(); }));
    // Inside a convex polygon of the plane z = 0 (either winding), up to rounding.
    auto inside = [](const rad::Vec3& p, std::span<const rad::Vec3> polygon) {
        for (std::size_t k = 0; k < polygon.size(); ++k) {
            const auto& a = polygon[k];
            const auto& b = polygon[(k + 1) % polygon.size()];
            const double side = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            if (std::abs(side) > 1e-12 &&
                (side > 0) != (rad::cross(polygon[1] - polygon[0], polygon[2] - polygon[0])[2] > 0))
                return false;
        }
        return std::abs(p[2]) < 1e-12;
    };
    rad::Rng rng(7, 0);
    int checked = 0;
    for (std::uint32_t node = 0; node < tree.nodes.size(); ++node) {
        const auto& n = tree.nodes[node];
        // Where each of the node's patches ends in its area, in leaf order.
        std::vector<double> ends;
        double total = 0;
        for (auto k = n.first; k < n.first + n.count; ++k)
            ends.push_back(total += mesh.patches[tree.leaf_order[k]].area);
        rad::Vec3 sum{0, 0, 0};
        const int points = 16000;
        for (int s = 0; s < points; ++s) {
            const double u = (s + rng.uniform()) / points;
            const auto x = geometry.point(node, u, rng.uniform(), rng.uniform());
            // std::upper_bound over the ends: the patch whose share of the area u falls in.
            const auto k = n.first + static_cast<std::uint32_t>(
                                         std::upper_bound(ends.begin(), ends.end() - 1, u * total) -
                                         ends.begin());
            const auto patch = tree.leaf_order[k];
            INFO("node " << node << ", u " << u);
            REQUIRE(inside(x.point, context.polygons[patch].points()));
            CHECK(x.normal[2] == mesh.patches[patch].normal[2]);
            sum = sum + x.point;
            ++checked;
        }
        // Area-uniform: the points' mean is the node's centroid (their mean's spread
        // is far below 1% of the node's size).
        const double size = geometry[node].box.diagonal();
        INFO("node " << node << " of " << n.count << " patches, centroid "
                     << geometry[node].centroid[0] << ", " << geometry[node].centroid[1]
                     << ", points' mean " << sum[0] / points << ", " << sum[1] / points);
        for (int c = 0; c < 2; ++c)
            CHECK(std::abs(sum[c] / points - geometry[node].centroid[c]) < 0.01 * size);
    }
    CHECK(checked > 150000);
}
