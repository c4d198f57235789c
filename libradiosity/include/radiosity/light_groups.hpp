// Light groups: radiosity is linear in emission, so one solve per group of emitters (all in
// one multi-channel solve) lets any mix of them (switched, dimmed, recoloured) be shown with no
// further solve.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/transport.hpp"

#include <string>
#include <vector>

namespace rad {

struct LightGroup {
    std::string name;
    std::vector<std::uint32_t> materials; // indices into the mesh's materials
};

// The groups of a mesh: first those `specs` define ("NAME=MAT[,MAT...]"), then one per
// remaining emitting material used by a patch, named after it. Throws InputError for a
// malformed spec, an unknown material (listing the known ones), a material in two groups, a
// name used twice, a group with no emission, or a mesh with nothing emitting.
std::vector<LightGroup> light_groups(const radfmt::MeshData& mesh,
                                     const std::vector<std::string>& specs);

// The emission with three channels per group, group after group: channel 3g + c is colour c
// of group g (materials outside every group emit nothing).
Channels grouped_emission(const radfmt::MeshData& mesh, const std::vector<LightGroup>& groups);

// Header fields naming each group's materials and their emission:
// light_group.NAME = "MAT=r,g,b MAT2=r,g,b".
void record_light_groups(radfmt::Header& header, const radfmt::MeshData& mesh,
                         const std::vector<LightGroup>& groups);

// A solution as the file stores it: with groups, each group's radiosity and their sum.
radfmt::RadiosityData radiosity_data(const Channels& solution,
                                     const std::vector<LightGroup>& groups);

// Patch radiosity for a mix of a file's groups: "NAME=s" (grey weight) or "NAME=r,g,b" per
// named group; unnamed groups keep weight 1, or 0 with `mix_only`. Throws InputError naming
// the known groups for an unknown one, and when the file has no groups at all.
// The weight of each of the file's groups in that mix.
std::vector<radfmt::Rgb> mix_weights(const radfmt::RadiosityData& rad,
                                     const std::vector<std::string>& mix, bool mix_only,
                                     const std::string& path);
std::vector<radfmt::Rgb> mix_light_groups(const radfmt::RadiosityData& rad,
                                          const std::vector<std::string>& mix, bool mix_only,
                                          const std::string& path);

} // namespace rad
