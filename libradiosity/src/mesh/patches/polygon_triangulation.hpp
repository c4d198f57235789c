// A planar polygon's triangles (internal header).
#pragma once
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace rad {

// Triangles over `ids` (the polygon's corners, in order; pts their positions, normal the
// polygon's) that cover the simple polygon, each wound as the polygon. Up to 64 corners, ear
// clipping; more, a CGAL constrained Delaunay triangulation (ear clipping's O(n^3) worst case
// hung on an OBJ face of 100,000 corners). A polygon that crosses itself gets a fan.
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& pts,
                                                              const std::vector<std::uint32_t>& ids,
                                                              const Vec3& normal);

} // namespace rad
