// Materials as the options and messages name them: what every stage that reads or changes a
// material shares (rad-mesh's passes, rad-solve's overrides, the checks' messages).
#pragma once
#include "radfmt/kinds.hpp"

#include <string>
#include <vector>

namespace rad {

struct MaterialOverride {
    std::string material;
    radfmt::Rgb value;
};
// "MATERIAL=r,g,b" or "MATERIAL=v" (grey); values finite and >= 0. `option` names the
// option in messages.
MaterialOverride parse_material_override(const std::string& spec, const std::string& option);

// "grey, lamp, white": the mesh's material names, for messages.
std::string material_names(const radfmt::MeshData& mesh);

// "0.5,0.25,1" as the header records colours.
std::string rgb_text(const radfmt::Rgb& value);

// A line about a material with the rad-solve option that would change it:
// "material 'NAME' <what> (<lead> rad-solve --OPTION NAME=r,g,b)".
std::string material_hint(const std::string& material, const std::string& what,
                          const std::string& lead, const std::string& option,
                          const radfmt::Rgb& value);

bool any_emitter(const radfmt::MeshData& mesh);

// One line per material used by a patch with a reflectance channel >= 1, with the
// rad-solve override that fixes it.
std::vector<std::string> reflectance_problems(const radfmt::MeshData& mesh);

} // namespace rad
