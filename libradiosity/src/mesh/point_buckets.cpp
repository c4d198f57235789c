// PointBuckets: points sorted by the cell of a uniform grid (kCells a side over their box).
#include "point_buckets.hpp"

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

std::vector<std::uint32_t> PointBuckets::on_segment(std::uint32_t a, std::uint32_t b,
                                                    double tolerance) const {
    const Vec3 pa = points_.position[a], pb = points_.position[b];
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
                if (c == a || c == b) continue;
                const Vec3 pc = points_.position[c];
                const double t = len2 > 0 ? dot(pc - pa, d) / len2 : 0;
                if (t <= 0 || t >= 1) continue;
                if (length(pa + d * t - pc) < tolerance && length(pc - pa) > tolerance &&
                    length(pc - pb) > tolerance)
                    found.emplace_back(t, c);
            }
        }
    std::sort(found.begin(), found.end());
    std::vector<std::uint32_t> out;
    for (const auto& [t, c] : found) out.push_back(c);
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
