// Points of a pass in the cells of a uniform grid, to find those lying on a segment: where an
// edge passes another face's or region's corner (a T-junction).
#pragma once
#include "mesh/regions/regions.hpp"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace rad::surfaces {

class PointBuckets {
  public:
    PointBuckets(const std::vector<std::uint32_t>& ids, const Points& points);
    // Points strictly inside segment ab (within `tolerance` of it), ordered from a to b.
    std::vector<std::uint32_t> on_segment(std::uint32_t a, std::uint32_t b, double tolerance) const;
    // Points within `tolerance` of segment ab, its ends included, ordered from a to b.
    std::vector<std::uint32_t> along(const Vec3& a, const Vec3& b, double tolerance) const;

  private:
    static constexpr std::int64_t kCells = 256; // the box's diagonal in cells
    using Cell = std::array<std::int64_t, 3>;
    Cell cell_of(const Vec3& p) const;
    // Points near segment pa-pb, except `skip`, by t along it: strictly between its ends
    // (slack < 0), or up to `slack` (of its length) past them.
    std::vector<std::pair<double, std::uint32_t>> near_segment(const Vec3& pa, const Vec3& pb,
                                                               double tolerance,
                                                               std::array<std::uint32_t, 2> skip,
                                                               double slack) const;
    static std::uint64_t code(const Cell& k) {
        return std::uint64_t((k[0] * (kCells + 1) + k[1]) * (kCells + 1) + k[2]);
    }
    const Points& points_;
    Box box_;
    double cell_ = 1;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> by_cell_; // (cell's code, point)
};

} // namespace rad::surfaces
