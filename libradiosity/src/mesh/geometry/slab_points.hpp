// A polygon's part within a slab (internal header).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace rad {

// Calls add(point) for the ends of the polygon's edges' parts within the slab
// lo <= p[axis] <= hi: its corners inside the slab and the points where its edges cross the
// slab's two sides. Their bounds are those of the polygon's part within the slab.
template <std::size_t N, class Add>
void for_each_slab_point(const std::vector<std::array<double, N>>& polygon, int axis, double lo,
                         double hi, Add&& add) {
    auto at = [](const std::array<double, N>& a, const std::array<double, N>& b, double t) {
        std::array<double, N> p;
        for (std::size_t c = 0; c < N; ++c) p[c] = a[c] + (b[c] - a[c]) * t;
        return p;
    };
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const auto& a = polygon[i];
        const auto& b = polygon[(i + 1) % polygon.size()];
        const double da = a[axis], db = b[axis];
        if (da >= lo && da <= hi) add(a);
        if ((da < lo) != (db < lo) && da != db) add(at(a, b, (lo - da) / (db - da)));
        if ((da > hi) != (db > hi) && da != db) add(at(a, b, (hi - da) / (db - da)));
    }
}

} // namespace rad
