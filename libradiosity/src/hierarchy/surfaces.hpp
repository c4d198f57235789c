// connected_surfaces: which patches form one surface, the unit a link may light as one
// (internal header).
#pragma once
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <vector>

namespace rad::hierarchy {

// Per patch, the index of its surface: the patches of one material on one plane (normal and
// offset rounded to a millionth of the scene's size) that are joined through shared corners.
// Surfaces are numbered in the order of their first patch. Two pillars' faces on one plane
// are two surfaces: what one sees, the other may not.
std::vector<std::uint32_t> connected_surfaces(const radfmt::MeshData& mesh);

// build_patch_tree over surfaces already found (`surface`: connected_surfaces(mesh)), for
// callers that need them again.
radfmt::LinkData build_surface_tree(const radfmt::MeshData& mesh,
                                    const std::vector<std::uint32_t>& surface);

} // namespace rad::hierarchy
