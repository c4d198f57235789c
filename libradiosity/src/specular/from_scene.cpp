// A material's specular part from MTL and glTF parameters, and the checks on it.
#include "radiosity/specular_materials.hpp"

#include "radiosity/error.hpp"
#include "radiosity/solve_policy.hpp"
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
constexpr double kPaneIor = 1.52; // Radiance's glass
} // namespace

Specular specular_from_mtl(const MtlSpecularInput& in) {
    Specular s;
    s.roughness = roughness_of(in.shininess);
    const double dielectric_ior = in.ior > 1 && in.ior <= 10 ? in.ior : 1.5;
    const double pane_ior = in.ior > 1 && in.ior <= 10 ? in.ior : kPaneIor;
    const bool filter_given = any_positive(in.filter);
    switch (in.illum) {
    case 3:
    case 5:
        if (!any_positive(in.specular)) return {};
        s.kind = in.illum == 3 ? SpecularKind::mirror : SpecularKind::fresnel;
        s.reflectance = clamped(in.specular);
        return s;
    case 6:
    case 7:
        s.kind = SpecularKind::dielectric;
        s.ior = dielectric_ior;
        s.transmittance = filter_given ? clamped(in.filter) : Rgb{{1, 1, 1}};
        return s;
    case 4:
    case 9:
        s.kind = SpecularKind::pane;
        s.ior = pane_ior;
        if (filter_given) {
            s.transmittance = clamped(in.filter);
        } else {
            const double t = in.dissolve < 1
                                 ? 1 - in.dissolve
                                 : 1 - brightest(in.diffuse) - pane_reflectance(pane_ior);
            s.transmittance = clamped(Rgb{{t, t, t}});
        }
        return s;
    default:
        break;
    }
    if (!(in.dissolve < 1)) return {};
    s.kind = SpecularKind::pane;
    s.ior = pane_ior;
    const double open = 1 - std::max(0.0, in.dissolve);
    for (int k = 0; k < 3; ++k) s.transmittance[k] = open * (filter_given ? in.filter[k] : 1.0);
    s.transmittance = clamped(s.transmittance);
    return s;
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

void check_specular_energy(const radfmt::Material& m, const std::string& where) {
    const auto& s = m.specular;
    if (!s.any()) return;
    double reflected[3] = {0, 0, 0}, transmitted[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        switch (s.kind) {
        case SpecularKind::mirror:
        case SpecularKind::fresnel:
            reflected[k] = s.reflectance[k];
            break;
        case SpecularKind::pane: {
            const auto shares =
                pane_shares(pane_transmissivity(s.transmittance[k], s.ior), s.ior, 1);
            reflected[k] = shares.reflected;
            transmitted[k] = shares.transmitted;
            break;
        }
        case SpecularKind::dielectric:
            break; // its boundary takes what the diffuse part leaves
        case SpecularKind::none:
            break;
        }
        const double sum = m.reflectance[k] + reflected[k] + transmitted[k];
        if (sum <= 1 + 1e-9) continue;
        static const char* channel[] = {"red", "green", "blue"};
        char text[400];
        std::snprintf(text, sizeof text,
                      " is a %s whose diffuse reflectance %.3g, specular reflectance %.3g and "
                      "transmittance %.3g add up to %.3g in %s, more than the light it gets: "
                      "lower Kd (the diffuse part), Ks or the transmission (Tf, 1 - d) so "
                      "that they add up to 1 at most",
                      radfmt::specular_kind_name(s.kind), m.reflectance[k], reflected[k],
                      transmitted[k], sum, channel[k]);
        throw InputError(where + text);
    }
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
