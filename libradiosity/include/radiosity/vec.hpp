// Small 3-vector helpers over radfmt::Vec3 (std::array<double,3>).
#pragma once
#include "radfmt/kinds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {
using radfmt::Rgb;

// Luminance-weighted sum of an RGB value (0.265 R + 0.670 G + 0.065 B, Radiance's weights,
// which add up to 1): the lux a unit of white luminance gives through a coefficient, the
// luminous share of a transmission.
inline double luminous(const Rgb& c) {
    return 0.265 * c[0] + 0.670 * c[1] + 0.065 * c[2];
}
using radfmt::Vec3;

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(const Vec3& a, double s) {
    return {a[0] * s, a[1] * s, a[2] * s};
}
inline Vec3 operator*(double s, const Vec3& a) {
    return a * s;
}
inline double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3& a) {
    return std::sqrt(dot(a, a));
}
inline Vec3 normalized(const Vec3& a) {
    const double l = length(a);
    return l > 0 ? a * (1.0 / l) : Vec3{0, 0, 0};
}
// An axis-aligned bounding box, empty until a point is added.
struct Box {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    void add(const Vec3& p) {
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], p[c]), hi[c] = std::max(hi[c], p[c]);
    }
    double diagonal() const { return length(hi - lo); }
    Vec3 centre() const { return (lo + hi) * 0.5; }
};
template <class Points> Box bounds(const Points& points) {
    Box box;
    for (const auto& p : points) box.add(p);
    return box;
}

inline bool finite(const Vec3& a) {
    return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}
// A unit vector orthogonal to the unit vector n.
inline Vec3 orthogonal(const Vec3& n) {
    return std::abs(n[0]) > 0.5 ? normalized(cross(n, Vec3{0, 1, 0}))
                                : normalized(cross(n, Vec3{1, 0, 0}));
}

// A cosine-weighted direction about the unit normal n, whose frame tu, tv completes, for
// u, v in [0, 1): Malley's method (a uniform point of the unit disc lifted to the sphere).
inline Vec3 cosine_direction(const Vec3& n, const Vec3& tu, const Vec3& tv, double u, double v) {
    const double radius = std::sqrt(u), phi = 2 * std::numbers::pi * v;
    return tu * (radius * std::cos(phi)) + tv * (radius * std::sin(phi)) +
           n * std::sqrt(std::max(0.0, 1 - u));
}

// Newell's method: a robust polygon normal whose length is twice the polygon's area.
template <class Points> Vec3 newell_normal(const Points& pts) {
    Vec3 n{0, 0, 0};
    const std::size_t count = pts.size();
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3& a = pts[i];
        const Vec3& b = pts[(i + 1) % count];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    return n;
}

// Area-weighted centroid of a planar polygon (fan of triangles from vertex 0).
template <class Points> Vec3 polygon_centroid(const Points& pts) {
    Vec3 sum{0, 0, 0};
    double total = 0;
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
        const double a = length(cross(pts[i] - pts[0], pts[i + 1] - pts[0]));
        sum = sum + (pts[0] + pts[i] + pts[i + 1]) * (a / 3.0);
        total += a;
    }
    if (total <= 0) {
        Vec3 mean{0, 0, 0};
        for (const auto& p : pts) mean = mean + p;
        return mean * (1.0 / pts.size());
    }
    return sum * (1.0 / total);
}
} // namespace rad
