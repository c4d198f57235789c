// Twins: patches on the same spot facing opposite ways (a two-sided surface's front and back),
// which rays, rasters and bakes tell apart by the side they meet.
#pragma once
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <vector>

namespace rad {

// For every patch, the patch on the same spot facing the other way (same corner positions,
// opposite normal), or -1.
std::vector<std::int64_t> find_twins(const radfmt::MeshData& mesh);

} // namespace rad
