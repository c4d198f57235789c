// Mirrors and glass from what scene files say: MTL's illumination models, Ks, Tf, Ni, d and
// glTF's metallic-roughness, transmission, ior and volume, as a material's specular part.
#pragma once
#include "radfmt/kinds.hpp"

#include <string>

namespace rad {

// What an MTL material says (tinyobjloader's defaults for what it leaves out: d 1, Ni 1), and
// which of its lines the file has: a value left out is no evidence of anything.
struct MtlSpecularInput {
    std::string name;
    int illum = -1;
    radfmt::Rgb diffuse{}, specular{}, filter{}; // Kd (times its texture's mean), Ks, Tf
    double ior = 1;                              // Ni
    double dissolve = 1;                         // d (1 - Tr)
    double shininess = -1;                       // Ns (-1: not given)
    bool states_filter = false, states_ior = false, states_dissolve = false; // Tf, Ni, d or Tr
};

// How a material is taken, and why.
struct MtlReading {
    radfmt::Specular specular;
    radfmt::Rgb diffuse{}; // the diffuse reflectance the solve uses (Kd, scaled to fit)
    // One line, "" for a plain material the file says nothing more of: what was decided from
    // which lines, and what was scaled or clamped to make it hold together.
    std::string why;
    bool changed = false; // a value differs from the file's (scaled or clamped)
};

// What exporters mean, over the letter of the MTL spec (docs/mirrors-and-glass.md, "What an
// MTL material means", with the exporters each rule comes from):
// - illum 3: a mirror of reflectance Ks; 5: Fresnel reflection from Ks at normal incidence.
// - illum 6, 7: the refracting boundary of a medium of index Ni (1.5 when not above 1)
//   filtered by Tf (Ks is not used: a smooth boundary reflects by Fresnel).
// - Glass is what the file marks as see-through: d < 1 (or Tr > 0) with any illum, a pane
//   transmitting (1 - d) x Tf whose diffuse part is Kd x d (the share that is covered); or,
//   with illum 4 or 9 ("glass on"), Tf stated below 1 (a pane transmitting Tf), an index Ni
//   other than 1 or a name that says glass (a pane transmitting what Kd and its own
//   reflection leave). illum 4 with d 1, Tf 1 and Ni 1 and no such name is opaque: Maya and
//   CityEngine write illum 4 on every material.
// - Tf 0 transmits nothing, whatever the illum. Tf alone makes nothing transmit.
// - Shares that add up to more than the light a surface gets are not refused: a pane's Kd is
//   lowered to what its reflection and transmission leave, a mirror's Kd and Ks are scaled
//   to add up to 1; Ks, Tf and d are clamped to [0, 1], an Ni that is no index (not in
//   (1, 10]) replaced by glass's. Each is said in `why`.
// Roughness from Ns (sqrt(2 / (Ns + 2)), Phong's lobe as a microfacet width), kept and treated
// as smooth.
MtlReading read_mtl_material(const MtlSpecularInput& in);

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

// Makes a material whose diffuse, specular and transmitted shares add up to more than 1 in a
// channel (at normal incidence) hold together: a pane's or a refracting boundary's diffuse
// part is lowered to what the glass leaves, a mirror's diffuse and specular parts are scaled
// to add up to 1. Returns what it did ("" when nothing needed doing).
std::string fit_specular_energy(radfmt::Material& material);

// The index of a pane of glass when its file gives none (Radiance's glass).
inline constexpr double kPaneIndex = 1.52;

// One line for rad-mesh and rad-info: "mirror, reflectance 0.95" and the like.
std::string specular_summary(const radfmt::Specular& specular);

// --thin NAME: a dielectric's boundary made a thin pane of its index, transmitting its
// filter at normal incidence (glazing drawn as one sheet).
radfmt::Specular as_thin_pane(const radfmt::Specular& specular, const radfmt::Rgb& diffuse);

} // namespace rad
