// Points and polygons in a plane's own coordinates (internal header), for the mesh passes.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rad {

using Point2d = std::array<double, 2>;

// Twice the signed area of the triangle o, a, b: > 0 when a to b turns left seen from o.
inline double cross2(const Point2d& o, const Point2d& a, const Point2d& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Even-odd test (ray crossing); a point on the outline may come out either way.
inline bool point_in_polygon(const Point2d& p, const std::vector<Point2d>& poly) {
    bool inside = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const auto &a = poly[i], &b = poly[j];
        if ((a[1] > p[1]) != (b[1] > p[1]) &&
            p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
            inside = !inside;
    }
    return inside;
}

// Distance from p to the segment ab.
inline double segment_distance(const Point2d& p, const Point2d& a, const Point2d& b) {
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double len2 = dx * dx + dy * dy;
    const double t =
        len2 > 0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2, 0.0, 1.0) : 0;
    return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// Whether p is within `tolerance` of the polygon's outline.
inline bool on_outline(const Point2d& p, const std::vector<Point2d>& poly, double tolerance) {
    for (std::size_t k = 0; k < poly.size(); ++k)
        if (segment_distance(p, poly[k], poly[(k + 1) % poly.size()]) <= tolerance) return true;
    return false;
}

} // namespace rad
