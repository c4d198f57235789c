// What a scene file says about its materials beyond what radiosity uses (Kd, Ke), kept for
// the checks rad-mesh makes before anything is solved.
#pragma once
#include "radfmt/kinds.hpp"

#include <span>
#include <string>
#include <vector>

namespace rad {

struct MaterialSource {
    radfmt::Rgb ambient{};        // Ka
    radfmt::Rgb specular{};       // Ks
    radfmt::Rgb transmittance{};  // Tf
    int illum = -1;               // the MTL illumination model, -1 when not given
    bool texture_missing = false; // map_Kd named but not found or unreadable
};

// The largest exitance accepted (W/m^2): 1.6e12 times the sun's, far past any lamp, and far
// enough below double's range that no sum of a solve overflows.
inline constexpr double kMaxEmission = 1e20;
// Throws InputError (`where`: the material's ... , e.g. "scene.obj: material 'lamp'") when
// the material emits more than kMaxEmission in a channel, naming `fix`.
void check_emission_limit(const radfmt::Material& material, const std::string& where,
                          const std::string& fix);

// Everything doubtful about the materials a mesh uses, one line each, all at once:
// reflectances >= 1 (with the rad-solve override that fixes each), a Ka brighter than 1 with
// no Ke ("did you mean Ke?"), mirrors and glass (a path tracer's specular or transparent
// material, which radiosity sees only through its small Kd), and no emitter at all.
// `sources` is per material of `mesh` (missing entries are not checked).
std::vector<std::string> material_warnings(const radfmt::MeshData& mesh,
                                           std::span<const MaterialSource> sources);

} // namespace rad
