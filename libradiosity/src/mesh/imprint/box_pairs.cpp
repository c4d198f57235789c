#include "mesh/imprint/box_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rad {

namespace {

bool overlap(const Box& a, const Box& b) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] > b.hi[k] || b.lo[k] > a.hi[k]) return false;
    return true;
}

bool empty(const Box& b) {
    return b.lo[0] > b.hi[0] || b.lo[1] > b.hi[1] || b.lo[2] > b.hi[2];
}

// The cell side: twice the median of the boxes' longest sides, and no finer than a 2^20 grid
// over everything.
double cell_side(const std::vector<Box>& boxes, const Box& all) {
    std::vector<double> sides;
    for (std::size_t k = 0; k < boxes.size(); k += std::max<std::size_t>(1, boxes.size() / 4096))
        if (!empty(boxes[k])) {
            const Vec3 d = boxes[k].hi - boxes[k].lo;
            sides.push_back(std::max({d[0], d[1], d[2]}));
        }
    std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
    const Vec3 span = all.hi - all.lo;
    const double widest = std::max({span[0], span[1], span[2]});
    return std::max({2 * sides[sides.size() / 2], widest / double(1 << 20), 1e-300});
}

} // namespace

void for_each_overlapping_pair(const std::vector<Box>& boxes,
                               const std::function<void(std::uint32_t, std::uint32_t)>& visit,
                               const std::vector<std::uint32_t>& groups) {
    auto group = [&](std::uint32_t b) { return groups.empty() ? kNoGroup : groups[b]; };
    auto one_group = [&](std::uint32_t a, std::uint32_t b) {
        return group(a) != kNoGroup && group(a) == group(b);
    };
    Box all;
    for (const auto& b : boxes)
        if (!empty(b)) all.add(b.lo), all.add(b.hi);
    if (empty(all)) return;
    const double side = cell_side(boxes, all);
    auto cell = [&](const Vec3& p, int k) {
        return static_cast<std::uint64_t>(std::max(0.0, std::floor((p[k] - all.lo[k]) / side)));
    };
    auto key = [](std::uint64_t i, std::uint64_t j, std::uint64_t k) {
        return (i << 42) | (j << 21) | k;
    };
    // Each box in every cell it overlaps; boxes over more than kMostCells go on a list of
    // their own, tried against every box.
    constexpr std::uint64_t kMostCells = 64;
    // (cell, group, box): a cell's boxes of one group next to each other, skipped together.
    std::vector<std::tuple<std::uint64_t, std::uint32_t, std::uint32_t>> entries;
    std::vector<std::uint32_t> large;
    for (std::uint32_t b = 0; b < boxes.size(); ++b) {
        if (empty(boxes[b])) continue;
        std::uint64_t lo[3], hi[3], count = 1;
        for (int k = 0; k < 3; ++k)
            lo[k] = cell(boxes[b].lo, k), hi[k] = cell(boxes[b].hi, k), count *= hi[k] - lo[k] + 1;
        if (count > kMostCells) {
            large.push_back(b);
            continue;
        }
        for (auto i = lo[0]; i <= hi[0]; ++i)
            for (auto j = lo[1]; j <= hi[1]; ++j)
                for (auto k = lo[2]; k <= hi[2]; ++k)
                    entries.emplace_back(key(i, j, k), group(b), b);
    }
    std::sort(entries.begin(), entries.end());
    auto cell_of = [](const auto& entry) { return std::get<0>(entry); };
    auto box_of = [](const auto& entry) { return std::get<2>(entry); };
    for (std::size_t start = 0; start < entries.size();) {
        std::size_t end = start;
        while (end < entries.size() && cell_of(entries[end]) == cell_of(entries[start])) ++end;
        std::size_t block_end = start; // the end of x's group's entries in this cell
        for (auto x = start; x < end; ++x) {
            if (x == block_end) { // x starts a group's run (a box of no group: a run of one)
                const auto g = std::get<1>(entries[x]);
                for (block_end = x + 1;
                     g != kNoGroup && block_end < end && std::get<1>(entries[block_end]) == g;)
                    ++block_end;
            }
            for (auto y = std::max(x + 1, block_end); y < end; ++y) {
                const auto a = box_of(entries[x]), b = box_of(entries[y]);
                if (!overlap(boxes[a], boxes[b])) continue;
                // Once: in the cell holding the lower corner of the two boxes' overlap.
                Vec3 corner;
                for (int k = 0; k < 3; ++k) corner[k] = std::max(boxes[a].lo[k], boxes[b].lo[k]);
                if (key(cell(corner, 0), cell(corner, 1), cell(corner, 2)) !=
                    cell_of(entries[start]))
                    continue;
                visit(std::min(a, b), std::max(a, b));
            }
        }
        start = end;
    }
    std::sort(large.begin(), large.end());
    for (std::size_t x = 0; x < large.size(); ++x)
        for (std::uint32_t b = 0; b < boxes.size(); ++b) {
            const auto a = large[x];
            if (b == a || one_group(a, b) || empty(boxes[b]) || !overlap(boxes[a], boxes[b]))
                continue;
            // A pair of two large boxes once, from the first.
            if (std::binary_search(large.begin(), large.end(), b) && b < a) continue;
            visit(std::min(a, b), std::max(a, b));
        }
}

} // namespace rad
