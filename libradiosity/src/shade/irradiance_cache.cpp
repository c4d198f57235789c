// The irradiance cache's records in a grid of cells, and their weighted mean at a point.
#include "radiosity/irradiance_cache.hpp"

#include <algorithm>
#include <cmath>

namespace rad {

IrradianceCache::IrradianceCache(std::vector<Record> records, double accuracy)
    : records_(std::move(records)), accuracy_(accuracy) {
    if (records_.empty()) return;
    // Cells of the median record's reach: a record sits in the few cells its sphere touches.
    std::vector<double> reach;
    for (const auto& r : records_) reach.push_back(accuracy_ * r.radius);
    std::nth_element(reach.begin(), reach.begin() + long(reach.size() / 2), reach.end());
    cell_ = std::max(reach[reach.size() / 2], 1e-9);
    for (std::uint32_t id = 0; id < records_.size(); ++id) {
        const auto& r = records_[id];
        const double extent = accuracy_ * r.radius;
        long lo[3], hi[3];
        for (int c = 0; c < 3; ++c) {
            lo[c] = cell_of(r.position[c] - extent);
            hi[c] = cell_of(r.position[c] + extent);
        }
        for (long i = lo[0]; i <= hi[0]; ++i)
            for (long j = lo[1]; j <= hi[1]; ++j)
                for (long k = lo[2]; k <= hi[2]; ++k) grid_[key(i, j, k)].push_back(id);
    }
}

long IrradianceCache::cell_of(double v) const {
    return static_cast<long>(std::floor(v / cell_));
}

IrradianceCache::Key IrradianceCache::key(long i, long j, long k) const {
    const auto part = [](long v) { return static_cast<std::uint64_t>(v) & 0x1FFFFFull; };
    return part(i) | part(j) << 21 | part(k) << 42;
}

bool IrradianceCache::lookup(const Vec3& x, const Vec3& n, Rgb& out) const {
    const auto found = grid_.find(key(cell_of(x[0]), cell_of(x[1]), cell_of(x[2])));
    if (found == grid_.end()) return false;
    double weight_sum = 0;
    Rgb sum{0, 0, 0};
    for (const auto id : found->second) {
        const auto& r = records_[id];
        const Vec3 d = x - r.position;
        // A record in front of the point (over its surface) sees other light: not reused.
        if (dot(d, n + r.normal) < -0.05 * r.radius) continue;
        const double e = length(d) / r.radius + std::sqrt(std::max(0.0, 1 - dot(n, r.normal)));
        if (!(e < accuracy_)) continue;
        const double w = 1 / std::max(e, 1e-9) - 1 / accuracy_;
        weight_sum += w;
        const Vec3 turn = cross(r.normal, n);
        for (int c = 0; c < 3; ++c) {
            const double moved =
                r.indirect[c] + dot(turn, r.rotational[c]) + dot(d, r.translational[c]);
            sum[c] += w * std::max(0.0, moved);
        }
    }
    if (!(weight_sum > 0)) return false;
    for (int c = 0; c < 3; ++c) out[c] = sum[c] / weight_sum;
    return true;
}

} // namespace rad
