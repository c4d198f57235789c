// Items of a plane in the squares of a uniform grid (internal header): what lies near a point
// is in the few squares around it. Insert each item into every square its box touches, then
// freeze (sort) before asking.
#pragma once
#include "mesh/geometry/polygon2d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rad {

class SquareIndex {
  public:
    explicit SquareIndex(double side) : side_(side) {}
    void insert(const Point2d& lo, const Point2d& hi, std::uint32_t item) {
        const auto a = square_of(lo), b = square_of(hi);
        for (auto i = a[0]; i <= b[0]; ++i)
            for (auto j = a[1]; j <= b[1]; ++j) entries_.push_back({{i, j}, item});
    }
    void freeze() { std::sort(entries_.begin(), entries_.end()); }
    bool empty() const { return entries_.empty(); }
    // Calls visit(item) for the items in the squares within `reach` squares of p's, square by
    // square (an item once per square it is in); stops when visit returns true, and says so.
    template <class Visit> bool find_near(const Point2d& p, int reach, Visit&& visit) const {
        const auto centre = square_of(p);
        for (auto i = centre[0] - reach; i <= centre[0] + reach; ++i)
            for (auto j = centre[1] - reach; j <= centre[1] + reach; ++j) {
                const Square square{i, j};
                auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{square, 0});
                for (; it != entries_.end() && it->first == square; ++it)
                    if (visit(it->second)) return true;
            }
        return false;
    }

  private:
    using Square = std::array<std::int64_t, 2>;
    using Entry = std::pair<Square, std::uint32_t>;
    Square square_of(const Point2d& p) const {
        return {std::int64_t(std::floor(p[0] / side_)), std::int64_t(std::floor(p[1] / side_))};
    }
    double side_;
    std::vector<Entry> entries_;
};

} // namespace rad
