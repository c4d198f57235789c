// A patch's geometry for consumers that need triangles or points: the one place that says
// how a quad or a polygon patch splits.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace rad {

// The triangles `patch` splits into, as indices into mesh.corners(patch): the fan from corner
// 0, {0, k, k + 1}. A triangle is itself, a quad {0, 1, 2} and {0, 2, 3}; a polygon is
// star-shaped from its corner 0 (the mesh format's promise), so its fan covers it, every
// triangle wound as the patch or flat (a straight corner).
std::vector<std::array<std::uint32_t, 3>> patch_triangles(const radfmt::MeshData& mesh,
                                                          std::size_t patch);

// The positions of the patch's corners, in order.
std::vector<Vec3> patch_points(const radfmt::MeshData& mesh, std::size_t patch);
// The same without allocating for a triangle or quad: in `few`, or for a polygon in `many`.
std::span<const Vec3> patch_points(const radfmt::MeshData& mesh, std::size_t patch,
                                   std::array<Vec3, 4>& few, std::vector<Vec3>& many);

} // namespace rad
