// The frame of a region (pass 3's input and pass 4's axes): its minimum-area rectangle.
#include "mesh/regions/regions.hpp"

#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>

namespace rad::surfaces {

namespace {

// The hull point farthest along `direction`, walking counter-clockwise from `from` while the
// next is farther (the hull is convex, so the distance along a direction rises, then falls).
std::size_t farthest_along(const std::vector<Point2>& hull, std::size_t from, const XY& direction) {
    auto along = [&](std::size_t k) {
        return hull[k].x() * direction[0] + hull[k].y() * direction[1];
    };
    for (std::size_t steps = 0; steps < hull.size(); ++steps) {
        const std::size_t next = (from + 1) % hull.size();
        if (!(along(next) > along(from))) break;
        from = next;
    }
    return from;
}

// The most along `direction` of the hull points within two of `at`: rounding can make
// neighbours of the farthest point look farther by a last bit, and the area must be what trying
// every point gives.
double most_near(const std::vector<Point2>& hull, std::size_t at, const XY& direction) {
    double most = -1e300;
    const std::size_t n = hull.size();
    for (std::size_t k = at + n - std::min<std::size_t>(2, n - 1); k <= at + n + 2; ++k) {
        const auto& p = hull[k % n];
        most = std::max(most, p.x() * direction[0] + p.y() * direction[1]);
    }
    return most;
}

} // namespace

// Rotating calipers: for each hull side, the farthest points ahead, behind and across are
// found by walking on from the previous side's (trying every point for every side was
// quadratic: a disc drawn as 20,000 slivers has that many hull points).
bool minimum_rectangle(const std::vector<Point2>& outline_points, GridFrame& frame) {
    std::vector<Point2> hull;
    CGAL::convex_hull_2(outline_points.begin(), outline_points.end(), std::back_inserter(hull));
    if (hull.size() < 3) return false;
    double best = 1e300;
    std::size_t ahead = 0, across = 0, behind = 0;
    bool first = true;
    for (std::size_t k = 0; k < hull.size(); ++k) {
        const auto& a = hull[k];
        const auto& b = hull[(k + 1) % hull.size()];
        const double len = std::hypot(b.x() - a.x(), b.y() - a.y());
        if (!(len > 0)) continue;
        const XY e1{(b.x() - a.x()) / len, (b.y() - a.y()) / len}, e2{-e1[1], e1[0]};
        // Counter-clockwise from the side: ahead, then across, then behind; each moves on.
        ahead = farthest_along(hull, first ? k : ahead, e1);
        across = farthest_along(hull, first ? ahead : across, e2);
        behind = farthest_along(hull, first ? across : behind, {-e1[0], -e1[1]});
        first = false;
        const double lo1 = -most_near(hull, behind, {-e1[0], -e1[1]}),
                     hi1 = most_near(hull, ahead, e1);
        const double lo2 = -most_near(hull, k, {-e2[0], -e2[1]}), hi2 = most_near(hull, across, e2);
        const double area = (hi1 - lo1) * (hi2 - lo2);
        if (area < best * (1 - 1e-12)) {
            best = area;
            frame.e1 = e1;
            frame.e2 = e2;
            frame.origin = {e1[0] * lo1 + e2[0] * lo2, e1[1] * lo1 + e2[1] * lo2};
            frame.length1 = hi1 - lo1;
            frame.length2 = hi2 - lo2;
        }
    }
    return best < 1e300 && frame.length1 > 0 && frame.length2 > 0;
}

double region_width(const Region& region, const Points& points) {
    std::vector<Point2> pts;
    for (const auto& edge : region.outline)
        for (const auto id : edge) {
            const auto xy = region.plane.to_2d(points.position[id]);
            pts.emplace_back(xy[0], xy[1]);
        }
    GridFrame frame;
    return minimum_rectangle(pts, frame) ? std::min(frame.length1, frame.length2) : 0;
}

} // namespace rad::surfaces
