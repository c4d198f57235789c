// CIE 117's Unified Glare Rating at an observer, from the luminaires' photometry.
#include "radiosity/glare.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {
namespace {
constexpr double kDegrees = 180 / std::numbers::pi;
}

bool inside_position_table(double height_ratio, double lateral_ratio) {
    constexpr double kSlack = 1e-9; // a luminaire on the table's edge is in it
    return height_ratio <= kMaxHeightRatio + kSlack && lateral_ratio <= kMaxLateralRatio + kSlack;
}

double unified_glare_rating(double lb, std::span<const GlareTerm> terms) {
    double sum = 0;
    for (const auto& term : terms) sum += term.contribution();
    if (terms.empty() || !(lb > 0) || !(sum > 0)) return std::nan("");
    return 8 * std::log10(0.25 / lb * sum);
}

double projected_opening_area(const Photometry& photometry, const Luminaire& luminaire,
                              const Vec3& toward) {
    const double down = std::max(0.0, dot(toward, luminaire.nadir));
    const double along_c0 = std::abs(dot(toward, luminaire.c0));
    const double along_c90 = std::abs(dot(toward, luminaire.c90));
    const double l = photometry.length, w = photometry.width, h = photometry.height;
    if (photometry.round) {
        const double sideways = std::sqrt(std::max(0.0, 1 - down * down));
        return std::numbers::pi * l * l / 4 * down + l * h * sideways;
    }
    return l * w * down + w * h * along_c0 + l * h * along_c90;
}

ObserverGlare observer_glare(const LuminaireSet& set, const RayScene* scene, const Vec3& eye,
                             const Vec3& view, double lb) {
    ObserverGlare glare;
    // The view's frame: right and up across the line of sight (the vertical is +Y).
    Vec3 right = cross(view, Vec3{0, 1, 0});
    right = length(right) > 1e-9 ? normalized(right) : Vec3{1, 0, 0};
    const Vec3 up = cross(right, view);
    for (std::size_t k = 0; k < set.luminaires.size(); ++k) {
        const auto& l = set.luminaires[k];
        const Vec3 offset = l.position - eye;
        const double distance = length(offset);
        if (!(distance > 0)) continue;
        const Vec3 s = offset * (1 / distance);
        const double ahead = dot(s, view), above = dot(s, up), across = dot(s, right);
        if (ahead <= 0 || above <= 0) {
            ++glare.behind_or_below;
            continue;
        }
        // CIE 117 defines the position index over its table's extent only: a luminaire past
        // it (far above or beside the line of sight) is left out, not capped.
        if (!inside_position_table(above / ahead, std::abs(across) / ahead)) {
            glare.outside_table.push_back(k);
            continue;
        }
        if (scene && !scene->visible(eye, l.position + s * (-1e-4 * distance))) {
            ++glare.hidden;
            continue;
        }
        const auto& photometry = set.photometries[l.photometry];
        const Vec3 toward = s * -1.0;
        const double area = projected_opening_area(photometry, l, toward); // m^2
        if (!(area > 0)) {
            ++glare.pointlike;
            continue;
        }
        const double metres = distance * set.metres_per_unit;
        GlareTerm term;
        term.luminaire = k;
        term.luminance = set.intensity(l, toward) / area;
        term.solid_angle = area / (metres * metres);
        term.sigma_deg = std::acos(std::clamp(ahead, -1.0, 1.0)) * kDegrees;
        term.tau_deg = std::atan2(std::abs(across), above) * kDegrees;
        term.position_index = guth_position_index(term.tau_deg, term.sigma_deg);
        glare.terms.push_back(term);
    }
    glare.ugr = unified_glare_rating(lb, glare.terms);
    return glare;
}

} // namespace rad
