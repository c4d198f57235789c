// PointBuckets: points sorted by the cell of a uniform grid (kCells a side over their box).
#include "mesh/geometry/point_buckets.hpp"

#include <algorithm>
#include <cmath>

namespace rad::surfaces {

PointBuckets::PointBuckets(const std::vector<std::uint32_t>& ids, const Points& points)
    : points_(points) {
    for (const auto id : ids) box_.add(points.position[id]);
    cell_ = std::max(1e-300, box_.diagonal() / kCells);
    by_cell_.reserve(ids.size());
    for (const auto id : ids) by_cell_.emplace_back(code(cell_of(points.position[id])), id);
    std::sort(by_cell_.begin(), by_cell_.end());
}

std::vector<std::pair<double, std::uint32_t>>
PointBuckets::near_segment(const Vec3& pa, const Vec3& pb, double tolerance,
                           std::array<std::uint32_t, 2> skip, double slack) const {
    const Vec3 d = pb - pa;
    const double len2 = dot(d, d);
    std::vector<std::pair<double, std::uint32_t>> found;
    Box box;
    box.add(pa);
    box.add(pb);
    const auto lo = cell_of(box.lo - Vec3{tolerance, tolerance, tolerance});
    const auto hi = cell_of(box.hi + Vec3{tolerance, tolerance, tolerance});
    for (auto i = lo[0]; i <= hi[0]; ++i)
        for (auto j = lo[1]; j <= hi[1]; ++j) {
            // Cells (i, j, lo..hi) are consecutive in the order of the codes.
            auto it = std::lower_bound(by_cell_.begin(), by_cell_.end(),
                                       std::pair{code({i, j, lo[2]}), std::uint32_t(0)});
            for (const auto last = code({i, j, hi[2]}); it != by_cell_.end() && it->first <= last;
                 ++it) {
                const auto c = it->second;
                if (c == skip[0] || c == skip[1]) continue;
                const Vec3 pc = points_.position[c];
                const double t = len2 > 0 ? dot(pc - pa, d) / len2 : 0;
                // slack < 0: strictly inside, as before; else up to slack past either end.
                if (slack < 0 ? t <= 0 || t >= 1 : t < -slack || t > 1 + slack) continue;
                if (length(pa + d * std::clamp(t, 0.0, 1.0) - pc) < tolerance)
                    found.emplace_back(t, c);
            }
        }
    std::sort(found.begin(), found.end());
    return found;
}

std::vector<std::uint32_t> PointBuckets::on_segment(std::uint32_t a, std::uint32_t b,
                                                    double tolerance) const {
    const Vec3 pa = points_.position[a], pb = points_.position[b];
    std::vector<std::uint32_t> out;
    for (const auto& [t, c] : near_segment(pa, pb, tolerance, {a, b}, -1))
        if (length(points_.position[c] - pa) > tolerance &&
            length(points_.position[c] - pb) > tolerance)
            out.push_back(c);
    return out;
}

std::vector<std::uint32_t> PointBuckets::along(const Vec3& a, const Vec3& b,
                                               double tolerance) const {
    const Vec3 d = b - a;
    const double len = length(d);
    const double slack = len > 0 ? tolerance / len : 0;
    std::vector<std::uint32_t> out;
    for (const auto& [t, c] : near_segment(a, b, tolerance, {kNone, kNone}, slack))
        out.push_back(c);
    return out;
}

// Clamped to the grid: no point lies outside it.
PointBuckets::Cell PointBuckets::cell_of(const Vec3& p) const {
    Cell k;
    for (int c = 0; c < 3; ++c)
        k[c] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor((p[c] - box_.lo[c]) / cell_)), 0, kCells);
    return k;
}

} // namespace rad::surfaces
