// Regions drawn both ways: which region is another's other side.
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rad::surfaces {

std::vector<std::uint32_t> twin_regions(const std::vector<Region>& regions,
                                        const radfmt::MeshData& faces,
                                        const std::vector<std::uint32_t>& weld) {
    std::vector<std::uint32_t> twin(regions.size(), kNone);
    std::vector<double> area(regions.size(), 0);
    for (std::uint32_t r = 0; r < regions.size(); ++r)
        for (const auto f : regions[r].faces) area[r] += faces.patches[f].area;
    // Each region's welded points, sorted: equal for two regions drawn on the same faces.
    std::map<std::vector<std::uint32_t>, std::vector<std::uint32_t>> by_points;
    for (std::uint32_t r = 0; r < regions.size(); ++r) {
        std::vector<std::uint32_t> key;
        for (const auto f : regions[r].faces) {
            const auto& p = faces.patches[f];
            for (int k = 0; k < p.corner_count(); ++k) key.push_back(weld[p.corners[k]]);
        }
        std::sort(key.begin(), key.end());
        key.erase(std::unique(key.begin(), key.end()), key.end());
        auto& earlier = by_points[std::move(key)];
        for (const auto e : earlier) {
            if (twin[e] == kNone &&
                dot(regions[e].plane.normal, regions[r].plane.normal) < -0.999 &&
                std::abs(area[r] - area[e]) <= 1e-9 * std::max(area[r], area[e])) {
                twin[r] = e;
                break;
            }
        }
        if (twin[r] == kNone) earlier.push_back(r);
    }
    return twin;
}

} // namespace rad::surfaces
