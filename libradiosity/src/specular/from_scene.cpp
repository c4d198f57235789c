// A material's specular part from MTL and glTF parameters, and the checks on it.
#include "radiosity/specular_materials.hpp"

#include "radiosity/error.hpp"
#include "radiosity/material_overrides.hpp"
#include "radiosity/specular.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rad {

namespace {
using radfmt::Rgb;
using radfmt::Specular;
using radfmt::SpecularKind;

bool any_positive(const Rgb& c) {
    return c[0] > 0 || c[1] > 0 || c[2] > 0;
}
double brightest(const Rgb& c) {
    return std::max({c[0], c[1], c[2]});
}
Rgb clamped(const Rgb& c) {
    Rgb out;
    for (int k = 0; k < 3; ++k) out[k] = std::clamp(std::isfinite(c[k]) ? c[k] : 0.0, 0.0, 1.0);
    return out;
}
double roughness_of(double shininess) {
    return shininess < 0 ? 0 : std::clamp(std::sqrt(2 / (shininess + 2)), 0.0, 1.0);
}
// The reflectance of a clear pane at normal incidence: both faces and the light between.
double pane_reflectance(double ior) {
    const double r = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    return 2 * r / (1 + r);
}

bool any_below_one(const Rgb& c) {
    return c[0] < 1 || c[1] < 1 || c[2] < 1;
}
bool all_zero(const Rgb& c) {
    return c[0] == 0 && c[1] == 0 && c[2] == 0;
}
std::string number_text(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}
void add_clause(std::string& text, const std::string& clause) {
    if (!clause.empty()) text += (text.empty() ? "" : "; ") + clause;
}

// Material names that say glass in the languages exporters' users write them in.
bool named_as_glass(const std::string& name) {
    std::string lower;
    for (const char c : name)
        lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* word : {"glas", "glazing", "glazed", "vitre", "verre", "vidrio", "vetro"})
        if (lower.find(word) != std::string::npos) return true;
    return false;
}

// The MTL's values brought into range, each change said: Ks, Tf and d are shares.
struct MtlValues {
    Rgb specular, filter;
    double dissolve = 1;
    std::string clamps;             // said whatever the material becomes
    std::string ks_clamp, tf_clamp; // said when a mirror, or glass, uses them
};
MtlValues clamped_values(const MtlSpecularInput& in) {
    MtlValues v{clamped(in.specular), clamped(in.filter), in.dissolve, "", "", ""};
    if (brightest(in.specular) > 1) v.ks_clamp = "Ks " + rgb_text(in.specular) + " clamped to 1";
    if (in.states_filter && brightest(in.filter) > 1)
        v.tf_clamp = "Tf " + rgb_text(in.filter) + " clamped to 1";
    if (!std::isfinite(in.dissolve) || in.dissolve < 0 || in.dissolve > 1) {
        v.dissolve = std::isfinite(in.dissolve) ? std::clamp(in.dissolve, 0.0, 1.0) : 1.0;
        add_clause(v.clamps,
                   "d " + number_text(in.dissolve) + " taken as " + number_text(v.dissolve));
    }
    return v;
}

// A glass's index from Ni: what the file says when it is one (in (1, 10]), else `fallback`,
// said when the file gave something else than 1.
double glass_index(const MtlSpecularInput& in, double fallback, std::string& clamps) {
    if (in.ior > 1 && in.ior <= 10) return in.ior;
    if (in.states_ior && in.ior != 1)
        add_clause(clamps, "Ni " + number_text(in.ior) +
                               " is no glass's index: " + number_text(fallback) + " used");
    return fallback;
}

// Why an illum 4 or 9 material is glass: the first line of the file that marks it see-through.
std::string glass_evidence(const MtlSpecularInput& in, const MtlValues& v) {
    const std::string illum = "illum " + std::to_string(in.illum);
    if (in.states_filter && any_below_one(v.filter))
        return "Tf " + rgb_text(v.filter) + " with " + illum;
    if (in.states_ior && in.ior != 1) return "Ni " + number_text(in.ior) + " with " + illum;
    if (named_as_glass(in.name)) return "its name, with " + illum;
    return "";
}

// A thin pane from what the file says: d's open share, else Tf, else what Kd and the
// glass's reflection leave.
Specular pane_of(const MtlSpecularInput& in, const MtlValues& v, double ior, Rgb& diffuse) {
    Specular s;
    s.kind = SpecularKind::pane;
    s.ior = ior;
    s.roughness = roughness_of(in.shininess);
    if (v.dissolve < 1) {
        for (int k = 0; k < 3; ++k) {
            s.transmittance[k] = (1 - v.dissolve) * (in.states_filter ? v.filter[k] : 1.0);
            diffuse[k] *= v.dissolve; // the covered share reflects; the open one lets through
        }
    } else if (in.states_filter && any_below_one(v.filter)) {
        s.transmittance = v.filter;
    } else {
        const double t = 1 - brightest(diffuse) - pane_reflectance(ior);
        s.transmittance = clamped(Rgb{{t, t, t}});
    }
    return s;
}

// What an illum 4 material that is taken as opaque says of transparency: "Tf 1,1,1, Ni 1, no d".
std::string stated_glass_lines(const MtlSpecularInput& in) {
    std::string text = in.states_filter ? "Tf " + rgb_text(in.filter) : "no Tf";
    text += in.states_ior ? ", Ni " + number_text(in.ior) : ", no Ni";
    return text + (in.states_dissolve ? ", d 1" : ", no d");
}

const char* kOpaqueAdvice = "--transmittance NAME=T makes it a pane";
} // namespace

MtlReading read_mtl_material(const MtlSpecularInput& in) {
    MtlReading out;
    out.diffuse = in.diffuse;
    auto v = clamped_values(in);
    std::string why;
    const bool glass_illum = in.illum == 4 || in.illum == 9;
    const bool tf_zero = in.states_filter && all_zero(v.filter);
    const bool refracting = in.illum == 6 || in.illum == 7;
    if ((in.illum == 3 || in.illum == 5) && any_positive(v.specular)) {
        out.specular.kind = in.illum == 3 ? SpecularKind::mirror : SpecularKind::fresnel;
        out.specular.reflectance = v.specular;
        out.specular.roughness = roughness_of(in.shininess);
    } else if (tf_zero && (refracting || glass_illum || v.dissolve < 1)) {
        why = "opaque: Tf 0 transmits nothing (" + std::string(kOpaqueAdvice) + ")";
    } else if (refracting) {
        out.specular.kind = SpecularKind::dielectric;
        out.specular.ior = glass_index(in, 1.5, v.clamps);
        out.specular.transmittance = in.states_filter ? v.filter : Rgb{{1, 1, 1}};
        out.specular.roughness = roughness_of(in.shininess);
    } else if (v.dissolve < 1) {
        out.specular = pane_of(in, v, glass_index(in, kPaneIndex, v.clamps), out.diffuse);
        why = "see-through: d " + number_text(v.dissolve) + " (a pane transmitting 1 - d" +
              (in.states_filter ? " times Tf" : "") +
              "; its diffuse part Kd x d, the covered share)";
    } else if (glass_illum) {
        const auto evidence = glass_evidence(in, v);
        if (evidence.empty()) {
            why = "opaque: illum " + std::to_string(in.illum) + " with " + stated_glass_lines(in) +
                  ": nothing marks it see-through (Maya and CityEngine write illum 4 on every "
                  "material; " +
                  kOpaqueAdvice + ")";
        } else {
            out.specular = pane_of(in, v, glass_index(in, kPaneIndex, v.clamps), out.diffuse);
            why = "see-through: " + evidence;
        }
    } else if (named_as_glass(in.name)) {
        why = "opaque, though named like glass: nothing in the file makes it see-through (" +
              std::string(kOpaqueAdvice) + ")";
    }
    if (out.specular.mirrors()) add_clause(v.clamps, v.ks_clamp);
    if (out.specular.transmits()) add_clause(v.clamps, v.tf_clamp);
    radfmt::Material m{"", out.diffuse, {}, out.specular};
    const auto fitted = fit_specular_energy(m);
    out.diffuse = m.reflectance;
    out.specular = m.specular;
    add_clause(why, v.clamps);
    add_clause(why, fitted);
    out.changed = !v.clamps.empty() || !fitted.empty();
    // Glass and mirrors say what they became, with why, in one line.
    out.why =
        out.specular.any() && !why.empty() ? specular_summary(out.specular) + ": " + why : why;
    return out;
}

Specular specular_from_pbr(const PbrSpecularInput& in, Rgb& diffuse) {
    const Rgb base = clamped(in.base);
    const double metallic = std::clamp(in.metallic, 0.0, 1.0);
    const double transmission = std::clamp(in.transmission, 0.0, 1.0);
    diffuse = base;
    Specular s;
    s.roughness = std::clamp(in.roughness, 0.0, 1.0);
    if (transmission > 0 && metallic < 1) {
        const double ior = in.ior >= 1 && in.ior <= 10 ? in.ior : 1.5;
        s.ior = ior;
        const double through = transmission * (1 - metallic);
        if (in.thickness > 0) {
            s.kind = SpecularKind::dielectric;
            s.transmittance = base;
        } else {
            s.kind = SpecularKind::pane;
            for (int k = 0; k < 3; ++k) s.transmittance[k] = through * base[k];
        }
        for (int k = 0; k < 3; ++k) diffuse[k] = base[k] * (1 - metallic) * (1 - transmission);
        if (s.kind == SpecularKind::pane)
            for (int k = 0; k < 3; ++k)
                diffuse[k] = std::min(
                    diffuse[k], std::max(0.0, 1 - s.transmittance[k] - pane_reflectance(ior)));
        return s;
    }
    if (metallic > 0 && s.roughness <= kMaxSmoothRoughness) {
        s.kind = SpecularKind::fresnel;
        for (int k = 0; k < 3; ++k) {
            s.reflectance[k] = metallic * base[k];
            diffuse[k] = (1 - metallic) * base[k];
        }
        return s;
    }
    return {};
}

std::string fit_specular_energy(radfmt::Material& m) {
    auto& s = m.specular;
    if (!s.any()) return "";
    Rgb reflected{}, transmitted{};
    for (int k = 0; k < 3; ++k) {
        if (s.mirrors()) {
            reflected[k] = s.reflectance[k];
        } else if (s.kind == SpecularKind::pane) {
            const auto shares =
                pane_shares(pane_transmissivity(s.transmittance[k], s.ior), s.ior, 1);
            reflected[k] = shares.reflected;
            transmitted[k] = shares.transmitted;
        }
        // A refracting boundary takes what the diffuse part leaves (optics.cpp).
    }
    // One factor for all channels keeps the colour.
    double scale = 1;
    for (int k = 0; k < 3; ++k) {
        const double sum = m.reflectance[k] + reflected[k] + transmitted[k];
        if (sum <= 1 + 1e-9) continue;
        if (s.mirrors())
            scale = std::min(scale, 1 / sum);
        else if (m.reflectance[k] > 0)
            scale = std::min(scale,
                             std::max(0.0, 1 - reflected[k] - transmitted[k]) / m.reflectance[k]);
    }
    if (scale >= 1) return "";
    const Rgb was = m.reflectance;
    for (int k = 0; k < 3; ++k) m.reflectance[k] *= scale;
    if (s.mirrors()) {
        const Rgb ks = s.reflectance;
        for (int k = 0; k < 3; ++k) s.reflectance[k] *= scale;
        return "Kd " + rgb_text(was) + " and Ks " + rgb_text(ks) +
               " add up to more than 1: both scaled by " + number_text(scale) + " to " +
               rgb_text(m.reflectance) + " and " + rgb_text(s.reflectance);
    }
    return "Kd " + rgb_text(was) +
           " with the glass's reflection and transmission adds up to more than 1: Kd scaled to " +
           rgb_text(m.reflectance);
}

std::string specular_summary(const Specular& s) {
    char text[200] = "";
    switch (s.kind) {
    case SpecularKind::none:
        return "no specular part";
    case SpecularKind::mirror:
        std::snprintf(text, sizeof text, "mirror, reflectance %s", rgb_text(s.reflectance).c_str());
        break;
    case SpecularKind::fresnel:
        std::snprintf(text, sizeof text, "mirror, reflectance %s at normal incidence (Fresnel)",
                      rgb_text(s.reflectance).c_str());
        break;
    case SpecularKind::pane:
        std::snprintf(text, sizeof text,
                      "thin pane of glass, index %.3g, transmittance %s at normal incidence", s.ior,
                      rgb_text(s.transmittance).c_str());
        break;
    case SpecularKind::dielectric:
        std::snprintf(text, sizeof text,
                      "refracting boundary of a medium of index %.3g behind its back, passage "
                      "filter %s",
                      s.ior, rgb_text(s.transmittance).c_str());
        break;
    }
    std::string out = text;
    if (s.roughness > 0) {
        char r[120];
        std::snprintf(r, sizeof r, "; roughness %.2g treated as smooth", s.roughness);
        out += r;
    }
    return out;
}

Specular as_thin_pane(const Specular& s, const Rgb& diffuse) {
    if (s.kind != SpecularKind::dielectric) return s;
    Specular pane = s;
    pane.kind = SpecularKind::pane;
    for (int k = 0; k < 3; ++k)
        pane.transmittance[k] =
            std::min(s.transmittance[k], std::max(0.0, 1 - diffuse[k] - pane_reflectance(s.ior)));
    return pane;
}

} // namespace rad
