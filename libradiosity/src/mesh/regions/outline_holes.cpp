// Pass 3a of mesh_surfaces: a region's small holes filled where something rises through them.
//
// A pipe through a floor, or a post on it that imprinting cut out, leaves a hole in the floor a
// few units across; well-shaped triangles around it are its size, so a hole a tenth of a cell
// across brings a ring of specks. Where every other region at the hole's points rises from the
// floor's plane, the ground inside lies within what rises there, and the floor covers it.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rad::surfaces {

namespace {

// The region's closed loops of pieces (indices into its pieces), each in order; loops through a
// point where more than two pieces meet are left out.
std::vector<std::vector<std::size_t>> simple_loops(const Region& region) {
    std::unordered_map<std::uint32_t, std::vector<std::size_t>> at;
    for (std::size_t k = 0; k < region.pieces.size(); ++k)
        for (const auto p : region.pieces[k]) at[p].push_back(k);
    std::vector<char> seen(region.pieces.size(), 0);
    std::vector<std::vector<std::size_t>> loops;
    for (std::size_t first = 0; first < region.pieces.size(); ++first) {
        if (seen[first]) continue;
        std::vector<std::size_t> loop;
        bool simple = true;
        std::size_t k = first;
        std::uint32_t p = region.pieces[first][1];
        while (!seen[k]) {
            seen[k] = 1;
            loop.push_back(k);
            const auto& list = at[p];
            if (list.size() != 2) {
                simple = false;
                break;
            }
            k = list[0] == k ? list[1] : list[0];
            p = region.pieces[k][0] == p ? region.pieces[k][1] : region.pieces[k][0];
        }
        if (simple && k == first && loop.size() >= 3) loops.push_back(std::move(loop));
    }
    return loops;
}

// The loop's corners in the region's plane, in order.
std::vector<Point2d> loop_polygon(const Region& region, const std::vector<std::size_t>& loop,
                                  const Points& points) {
    std::vector<Point2d> polygon;
    std::uint32_t p = region.pieces[loop.front()][0];
    for (const auto k : loop) {
        const auto xy = region.plane.to_2d(points.position[p]);
        polygon.push_back({xy[0], xy[1]});
        p = region.pieces[k][0] == p ? region.pieces[k][1] : region.pieces[k][0];
    }
    return polygon;
}

double diagonal(const std::vector<Point2d>& polygon) {
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto& q : polygon)
        for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], q[i]), hi[i] = std::max(hi[i], q[i]);
    return std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
}

double area(const std::vector<Point2d>& polygon) {
    double twice = 0;
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
        twice += polygon[j][0] * polygon[i][1] - polygon[i][0] * polygon[j][1];
    return std::abs(twice) / 2;
}

// Whether the loop bounds a hole: beside its first side, the point inside the loop is outside
// the region.
bool is_hole(const Region& region, const std::vector<Point2d>& polygon) {
    const auto &a = polygon[0], &b = polygon[1];
    const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    if (!(len > 0)) return false;
    const double step = 1e-4 * len;
    for (const double side : {1.0, -1.0}) {
        const Point2d q{(a[0] + b[0]) / 2 - side * dy / len * step,
                        (a[1] + b[1]) / 2 + side * dx / len * step};
        if (point_in_polygon(q, polygon)) return !region.contains(Point2(q[0], q[1]));
    }
    return false;
}

} // namespace

void fill_small_holes(std::vector<Region>& regions, const Points& points, OutlineGrowth& growth) {
    const RisingWalls walls(regions);
    for (std::uint32_t r = 0; r < regions.size(); ++r) {
        auto& region = regions[r];
        if (!(region.cell > 0) || !region.quad_sides.empty()) continue;
        std::vector<char> drop(region.pieces.size(), 0);
        std::vector<std::vector<Point2d>> filled;
        for (const auto& loop : simple_loops(region)) {
            const auto polygon = loop_polygon(region, loop, points);
            if (!(diagonal(polygon) < region.cell / 10)) continue;
            const bool covered = std::all_of(loop.begin(), loop.end(), [&](std::size_t k) {
                const auto [a, b] = region.pieces[k];
                return walls.along_piece(r, a, b) && walls.around_point(r, a);
            });
            if (!covered || !is_hole(region, polygon)) continue;
            for (const auto k : loop) drop[k] = 1;
            ++growth.holes, growth.area += area(polygon);
            filled.push_back(polygon);
        }
        if (filled.empty()) continue;
        std::vector<std::array<std::uint32_t, 2>> kept;
        for (std::size_t k = 0; k < region.pieces.size(); ++k)
            if (!drop[k]) kept.push_back(region.pieces[k]);
        region.pieces = std::move(kept);
        for (auto& polygon : filled) cover(region, std::move(polygon));
        region.outline = region.pieces;
    }
}

} // namespace rad::surfaces
