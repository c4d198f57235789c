#include "sampling.hpp"

#include <algorithm>

namespace rad::ff {

void gauss_legendre(int m, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(m, 0);
    weights.assign(m, 0);
    for (int i = 0; i < m; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (m + 0.5));
        double dp = 1;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= m; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = m * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-15) break;
        }
        nodes[i] = 0.5 * (1 - x);
        weights[i] = 1.0 / ((1 - x * x) * dp * dp);
    }
}

std::vector<PatchPolygon> fan_triangles(const PatchPolygon& g) {
    const auto points = g.points();
    std::vector<PatchPolygon> out;
    for (std::size_t k = 1; k + 1 < points.size(); ++k)
        out.push_back({{points[0], points[k], points[k + 1], Vec3{}}, 3});
    return out;
}

Vec3 patch_point(const PatchPolygon& g, double s, double t, double& jacobian) {
    const auto& c = g.corners;
    if (g.count == 4) {
        const Vec3 p = c[0] * ((1 - s) * (1 - t)) + c[1] * (s * (1 - t)) + c[2] * (s * t) +
                       c[3] * ((1 - s) * t);
        const Vec3 ds = (c[1] - c[0]) * (1 - t) + (c[2] - c[3]) * t;
        const Vec3 dt = (c[3] - c[0]) * (1 - s) + (c[2] - c[1]) * s;
        jacobian = length(cross(ds, dt));
        return p;
    }
    const Vec3 p = c[0] + (c[1] - c[0]) * s + (c[2] - c[1]) * (s * t);
    jacobian = length(cross(c[1] - c[0], c[2] - c[1])) * s;
    return p;
}

std::vector<Sample> gauss_samples(const PatchPolygon& g, double area,
                                  const std::vector<double>& nodes,
                                  const std::vector<double>& weights) {
    if (g.is_polygon()) {
        std::vector<Sample> out;
        for (const auto& triangle : fan_triangles(g))
            for (const auto& s : gauss_samples(triangle, area, nodes, weights)) out.push_back(s);
        return out;
    }
    std::vector<Sample> out;
    for (std::size_t a = 0; a < nodes.size(); ++a)
        for (std::size_t b = 0; b < nodes.size(); ++b) {
            double jacobian = 0;
            const Vec3 p = patch_point(g, nodes[a], nodes[b], jacobian);
            out.push_back({p, weights[a] * weights[b] * jacobian / area});
        }
    return out;
}

Vec3 uniform_point(std::span<const Vec3> poly, std::span<const double> cdf, double u0, double u1,
                   double u2) {
    return fan_triangle_point(poly, pick_fan_triangle(cdf, u0), u1, u2);
}

std::vector<double> fan_cdf(std::span<const Vec3> poly) {
    std::array<double, 2> few;
    std::vector<double> many;
    const auto cdf = fan_cdf(poly, few, many);
    return {cdf.begin(), cdf.end()};
}

std::span<const double> fan_cdf(std::span<const Vec3> poly, std::array<double, 2>& few,
                                std::vector<double>& many) {
    const std::size_t n = poly.size() < 3 ? 0 : poly.size() - 2;
    double* cdf = few.data();
    if (n > few.size()) {
        many.resize(n);
        cdf = many.data();
    }
    double total = 0;
    for (std::size_t k = 0; k < n; ++k) {
        total += length(cross(poly[k + 1] - poly[0], poly[k + 2] - poly[0]));
        cdf[k] = total;
    }
    for (std::size_t k = 0; k < n; ++k) cdf[k] = total > 0 ? cdf[k] / total : 1;
    return {cdf, n};
}

std::vector<Vec3> clip_to_front(std::span<const Vec3> poly, const Vec3& point, const Vec3& normal) {
    std::vector<Vec3> out;
    clip_to_front(poly, point, normal, out);
    return out;
}

void clip_to_front(std::span<const Vec3> poly, const Vec3& point, const Vec3& normal,
                   std::vector<Vec3>& out) {
    out.clear();
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3& a = poly[k];
        const Vec3& b = poly[(k + 1) % n];
        const double da = dot(a - point, normal), db = dot(b - point, normal);
        if (da >= 0) out.push_back(a);
        if ((da > 0 && db < 0) || (da < 0 && db > 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
}

double radical_inverse(std::uint64_t i, std::uint64_t base) {
    double inv = 1.0 / base, f = inv, r = 0;
    while (i) {
        r += f * (i % base);
        i /= base;
        f *= inv;
    }
    return r;
}

int points_per_axis(int samples) {
    return std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, samples)))));
}

} // namespace rad::ff
