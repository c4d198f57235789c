// The frame of a region (pass 3's input and pass 4's axes): its minimum-area rectangle.
#include "regions.hpp"

#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>

namespace rad::surfaces {

bool minimum_rectangle(const std::vector<Point2>& outline_points, GridFrame& frame) {
    std::vector<Point2> hull;
    CGAL::convex_hull_2(outline_points.begin(), outline_points.end(), std::back_inserter(hull));
    if (hull.size() < 3) return false;
    double best = 1e300;
    for (std::size_t k = 0; k < hull.size(); ++k) {
        const auto& a = hull[k];
        const auto& b = hull[(k + 1) % hull.size()];
        const double len = std::hypot(b.x() - a.x(), b.y() - a.y());
        if (!(len > 0)) continue;
        const XY e1{(b.x() - a.x()) / len, (b.y() - a.y()) / len}, e2{-e1[1], e1[0]};
        double lo1 = 1e300, hi1 = -1e300, lo2 = 1e300, hi2 = -1e300;
        for (const auto& p : hull) {
            const double s = p.x() * e1[0] + p.y() * e1[1], t = p.x() * e2[0] + p.y() * e2[1];
            lo1 = std::min(lo1, s), hi1 = std::max(hi1, s), lo2 = std::min(lo2, t),
            hi2 = std::max(hi2, t);
        }
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
