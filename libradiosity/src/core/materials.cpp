#include "radiosity/materials.hpp"

#include "radiosity/error.hpp"
#include "radiosity/material_overrides.hpp"

#include <algorithm>
#include <cstdio>

namespace rad {

namespace {
double brightest(const radfmt::Rgb& c) {
    return std::max({c[0], c[1], c[2]});
}
} // namespace

std::vector<std::string> material_warnings(const radfmt::MeshData& mesh,
                                           std::span<const MaterialSource> sources) {
    auto lines = reflectance_problems(mesh);
    for (auto& line : lines) line += ": a reflectance >= 1 does not converge";
    std::vector<bool> used(mesh.materials.size(), false);
    for (const auto& p : mesh.patches) used[p.material] = true;
    for (std::size_t m = 0; m < mesh.materials.size() && m < sources.size(); ++m) {
        const auto& mat = mesh.materials[m];
        const auto& source = sources[m];
        if (!used[m]) continue;
        const bool emits = mat.emits();
        if (!emits && brightest(source.ambient) > 1) {
            lines.push_back(material_hint(mat.name,
                                          "has Ka " + rgb_text(source.ambient) +
                                              " (brighter than 1) and no Ke: did you mean Ke?",
                                          "", "emission", source.ambient));
        }
        // Illumination models 3 to 9 are reflection and refraction (MTL spec); a strong Ks
        // or Tf over a weak Kd says the same: radiosity keeps only the diffuse part.
        const bool specular =
            (source.illum >= 3 && source.illum <= 9) ||
            brightest(source.specular) > brightest(mat.reflectance) ||
            brightest(source.transmittance) > 0.5 * (1 - brightest(mat.reflectance));
        // A dark Kd with its texture missing is that, whatever Ks says: the colour is lost.
        if (!emits && source.texture_missing && brightest(mat.reflectance) < 0.1) {
            lines.push_back("material '" + mat.name + "' has Kd " + rgb_text(mat.reflectance) +
                            " and its map_Kd texture is missing: radiosity sees it nearly black "
                            "(put the texture where the MTL says, or rad-solve --reflectance " +
                            mat.name + "=r,g,b)");
            continue;
        }
        // A mirror or glass the chain now follows (its specular part) is no warning.
        if (!emits && specular && !mat.specular.any() && brightest(mat.reflectance) < 0.1) {
            std::string line = "material '";
            line += mat.name;
            line += "' is a mirror or glass in its MTL (";
            if (source.illum >= 0) {
                line += "illum ";
                line += std::to_string(source.illum);
                line += ", ";
            }
            line += "Ks ";
            line += rgb_text(source.specular);
            line += "): radiosity is diffuse only and sees its Kd ";
            line += rgb_text(mat.reflectance);
            line += ", nearly black (rad-solve --reflectance ";
            line += mat.name;
            line += "=r,g,b gives it a diffuse colour)";
            lines.push_back(std::move(line));
        }
    }
    if (!any_emitter(mesh))
        lines.push_back("no surface emits light: no material has an emission (Ke > 0), and a "
                        "lamp the modelling program kept as a light (Blender's lamps, say), not "
                        "as a surface, is not read; light the scene with a material or "
                        "group that should glow (rad-solve --emission NAME=r,g,b), luminaires "
                        "where the lamps are (rad-ff --luminaires LAYOUT: rows of x, y, z and an "
                        "IES or LDT file; then rad-solve --direct), or the sky through its "
                        "windows (rad-ff --sky reinhart:1; then rad-solve --direct)");
    return lines;
}

void check_emission_limit(const radfmt::Material& material, const std::string& where,
                          const std::string& fix) {
    const double most =
        std::max({material.emission[0], material.emission[1], material.emission[2]});
    if (!(most > kMaxEmission)) return;
    char text[160];
    std::snprintf(text, sizeof text,
                  " emits %.3g W/m^2, over the limit of %.0e (1.6e12 suns): a solve would "
                  "overflow; ",
                  most, kMaxEmission);
    throw InputError(where + text + fix);
}

} // namespace rad
