// Mirrors and glass from what scene files say: MTL's illumination models, Ks, Tf, Ni, d and
// glTF's metallic-roughness, transmission, ior and volume, as a material's specular part.
#pragma once
#include "radfmt/kinds.hpp"

#include <string>

namespace rad {

// What an MTL material says (tinyobjloader's defaults for what it leaves out: d 1, Ni 1).
struct MtlSpecularInput {
    int illum = -1;
    radfmt::Rgb diffuse{}, specular{}, filter{}; // Kd, Ks, Tf
    double ior = 1;                              // Ni
    double dissolve = 1;                         // d (1 - Tr)
    double shininess = -1;                       // Ns (-1: not given)
};
// illum 3: a mirror of reflectance Ks; 5: Fresnel reflection from Ks at normal incidence;
// 6, 7: refraction, the boundary of a medium of index Ni (1.5 when not above 1) filtered by
// Tf (Ks is not used: a smooth boundary reflects by Fresnel); 4, 9 ("glass on"): a thin pane
// transmitting Tf at normal incidence (else 1 - d, else what Kd and the glass's own
// reflection leave); any other with d < 1: a pane transmitting (1 - d) x Tf. Tf alone makes
// nothing transmit (exporters write Tf 1 1 1 on every material). Roughness from Ns
// (sqrt(2 / (Ns + 2)), Phong's lobe as a microfacet width), kept and treated as smooth.
radfmt::Specular specular_from_mtl(const MtlSpecularInput& in);

// What a glTF metallic-roughness material says.
struct PbrSpecularInput {
    radfmt::Rgb base{}; // baseColorFactor (times its texture's mean)
    double metallic = 0, roughness = 1;
    double transmission = 0; // KHR_materials_transmission
    double ior = 1.5;        // KHR_materials_ior
    double thickness = 0;    // KHR_materials_volume (0: thin-walled)
};
// Metallic m with roughness under kMaxSmoothRoughness: a mirror of reflectance m x base
// (Fresnel-Schlick from it) beside a diffuse part (1 - m) x base; a rougher metal's lobe is
// too wide to be a mirror and is kept diffuse (base colour, as before). Transmission t: a thin
// pane (thickness 0) transmitting t x base at normal incidence, or the boundary of a medium of
// index ior (thickness > 0) filtered by base; the diffuse part is (1 - t) x what is left.
// Sets `diffuse` to the diffuse part.
inline constexpr double kMaxSmoothRoughness = 0.3;
radfmt::Specular specular_from_pbr(const PbrSpecularInput& in, radfmt::Rgb& diffuse);

// Refuses (InputError: `where`, e.g. "scene.obj: material 'glass'", and the fix) a material
// whose diffuse, specular and transmitted shares add up to more than 1 in a channel (at
// normal incidence).
void check_specular_energy(const radfmt::Material& material, const std::string& where);

// One line for rad-mesh and rad-info: "mirror, reflectance 0.95" and the like.
std::string specular_summary(const radfmt::Specular& specular);

// --thin NAME: a dielectric's boundary made a thin pane of its index, transmitting its
// filter at normal incidence (glazing drawn as one sheet).
radfmt::Specular as_thin_pane(const radfmt::Specular& specular, const radfmt::Rgb& diffuse);

} // namespace rad
