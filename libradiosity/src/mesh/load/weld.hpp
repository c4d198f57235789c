// Vertices welded by position (internal header): faces written with their own copies of
// shared corners still connect, for the orientation checks and duplicate removal.
#pragma once
#include "radiosity/vec.hpp"

#include <cstdint>
#include <vector>

namespace rad {

// One id per distinct position, on a grid far finer than any sensible feature (1e-9 of the
// scene's size); ids are numbered in order of first appearance.
std::vector<std::uint32_t> weld_by_position(const std::vector<Vec3>& vertices);

} // namespace rad
