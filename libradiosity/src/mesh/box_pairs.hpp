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
void for_each_overlapping_pair(const std::vector<Box>& boxes,
                               const std::function<void(std::uint32_t, std::uint32_t)>& visit);

} // namespace rad
