// Two-sided surfaces: a patch receives and reflects light on the side its normal points to,
// so a thin thing modelled as one sheet (a curtain, a leaf, a table top as a plane) gets a
// second patch on the same spot facing the other way, with its own radiosity.
#pragma once
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rad {

struct TwoSidedReport {
    std::size_t back_patches = 0;
    std::vector<std::string> unlit_back_materials; // emitters whose back side got no emission
};

// Adds a back patch (same corners in reverse order, opposite normal, same group) after the
// existing patches for every patch whose group or material is named in `selection` ("all":
// every patch). The back has the front's reflectance; an emitting material's back emits
// only with `emission_on_both_sides`, otherwise it gets a copy of the material named
// "<name>.back" with zero emission. Throws InputError listing the groups and materials for a
// name that is neither. Patches that already have a twin are left alone.
TwoSidedReport make_two_sided(radfmt::MeshData& mesh, const std::vector<std::string>& selection,
                              bool emission_on_both_sides);

// The back of `front`: its corners in reverse order (a polygon from the same first corner, the
// one it is star-shaped from), the opposite normal, the rest the same. A polygon's corners
// are added to `mesh`.
radfmt::Patch back_of(radfmt::MeshData& mesh, const radfmt::Patch& front);

} // namespace rad
