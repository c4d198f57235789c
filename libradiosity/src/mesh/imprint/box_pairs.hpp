// Pairs of overlapping boxes among many (the broad phase of contact finding).
#pragma once
#include "radiosity/vec.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace rad {

// Calls visit(a, b) once for each pair a < b of boxes that overlap (closed: touching
// counts), in no set order. Boxes with lo > hi on an axis (empty) take no part. A uniform grid
// of cells about twice the typical box: a sweep along one axis is quadratic on a finely
// triangulated wall, and a segment tree slows down on boxes that share an extent (every face
// of one floor has the same height).
//
// With `groups` (one per box, or empty), two boxes of one group are not a pair (kNoGroup is
// no group): the slivers of a fan all hold its hub, so every pair of them overlaps, and a
// caller that does not want faces with a corner in common groups them by that corner.
constexpr std::uint32_t kNoGroup = 0xffffffffu;
void for_each_overlapping_pair(const std::vector<Box>& boxes,
                               const std::function<void(std::uint32_t, std::uint32_t)>& visit,
                               const std::vector<std::uint32_t>& groups = {});

} // namespace rad
