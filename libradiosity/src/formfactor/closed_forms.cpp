// Closed-form form factors: point to polygon (Lambert's contour integral) and Howell's
// rectangle configurations, the independent references the tests check the methods against.
#include "radiosity/formfactor.hpp"

#include "formfactor/angle.hpp"

#include <cmath>
#include <numbers>

namespace rad {

namespace {
constexpr double kPi = std::numbers::pi;
}

double contour_edge_term(const Vec3& a, const Vec3& b, const Vec3& normal) {
    const Vec3 c = cross(a, b);
    const double s = length(c);
    if (s < 1e-15) return 0;
    const double angle = ff::angle_from_sides(s, dot(a, b));
    return angle * dot(normal, c) / s;
}

double point_to_polygon_form_factor(const Vec3& point, const Vec3& normal,
                                    std::span<const Vec3> polygon) {
    const std::size_t n = polygon.size();
    if (n == 0) return 0;
    // Each corner's direction once, each edge taking its two ends.
    const Vec3 first = normalized(polygon[0] - point);
    Vec3 from = first;
    double sum = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3 to = k + 1 < n ? normalized(polygon[k + 1] - point) : first;
        sum += contour_edge_term(from, to, normal);
        from = to;
    }
    return std::abs(sum) / (2 * kPi);
}

double parallel_rectangles_form_factor(double a, double b, double c) {
    const double x = a / c, y = b / c;
    const double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
    return 2 / (kPi * x * y) *
           (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
            x * y1 * std::atan(x / y1) + y * x1 * std::atan(y / x1) - x * std::atan(x) -
            y * std::atan(y));
}

double perpendicular_rectangles_form_factor(double h, double l, double w) {
    // From rectangle of width w (perpendicular to the common edge of length l) to the
    // rectangle of height h: H = h/l, W = w/l.
    const double H = h / l, W = w / l;
    const double H2 = H * H, W2 = W * W, HW = std::sqrt(H2 + W2);
    const double term = W * std::atan(1 / W) + H * std::atan(1 / H) - HW * std::atan(1 / HW) +
                        0.25 * std::log((1 + W2) * (1 + H2) / (1 + W2 + H2) *
                                        std::pow(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2)), W2) *
                                        std::pow(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)), H2));
    return term / (kPi * W);
}

} // namespace rad
