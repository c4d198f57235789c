#include "mesh/load/weld.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace rad {

std::vector<std::uint32_t> weld_by_position(const std::vector<Vec3>& vertices) {
    const auto box = bounds(vertices);
    const Vec3& lo = box.lo;
    const double cell = std::max(1e-300, 1e-9 * box.diagonal());
    std::map<std::array<long long, 3>, std::uint32_t> ids;
    std::vector<std::uint32_t> out(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        std::array<long long, 3> key;
        for (int c = 0; c < 3; ++c) key[c] = std::llround((vertices[i][c] - lo[c]) / cell);
        out[i] = ids.try_emplace(key, static_cast<std::uint32_t>(ids.size())).first->second;
    }
    return out;
}

} // namespace rad
