// Discomfort glare from luminaires: CIE 117's Unified Glare Rating at an observer,
// UGR = 8 log10(0.25 / Lb x sum(L^2 omega / p^2)), from each luminaire's luminance toward the
// eye (its intensity over its projected luminous opening), the solid angle of that opening,
// Guth's position index, and the background luminance Lb (the indirect illuminance at the eye
// over pi, from the solution).
#pragma once
#include "radiosity/luminaires.hpp"
#include "radiosity/position_index.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/vec.hpp"

#include <span>
#include <string>
#include <vector>

namespace rad {

// The extent of CIE 117's position-index table (Luckiesh and Guth's, as the IES tabulates it):
// H/R, the source's height above the line of sight over its distance along it, up to 1.9;
// T/R, its distance to the side over R, up to 3.
inline constexpr double kMaxHeightRatio = 1.9, kMaxLateralRatio = 3.0;
bool inside_position_table(double height_ratio, double lateral_ratio);

struct GlareTerm {
    std::size_t luminaire = 0; // index into LuminaireSet::luminaires
    double luminance = 0;      // cd/m^2 toward the eye
    double solid_angle = 0;    // sr
    double position_index = 0;
    double tau_deg = 0, sigma_deg = 0;
    double contribution() const {
        return luminance * luminance * solid_angle / (position_index * position_index);
    }
};

// The UGR of these terms over background luminance `lb` (cd/m^2); NaN without terms.
double unified_glare_rating(double lb, std::span<const GlareTerm> terms);

// The luminous opening's area (m^2) seen from the unit direction `toward` (from the
// luminaire to the eye): its bottom by the cosine from the nadir, its sides (a box of
// length x width x height along C0, C90 and the nadir; a disc or cylinder when round).
double projected_opening_area(const Photometry& photometry, const Luminaire& luminaire,
                              const Vec3& toward);

struct ObserverGlare {
    std::vector<GlareTerm> terms; // the luminaires that count: seen, in front, above the eye
    long behind_or_below = 0;     // in the set but behind the eye or below the line of sight
    long hidden = 0;              // blocked by the scene
    long pointlike = 0;           // no luminous opening in their file: no luminance
    // In front and above, but past CIE 117's position-index table (inside_position_table):
    // left out, by index into LuminaireSet::luminaires.
    std::vector<std::size_t> outside_table;
    double ugr = 0; // NaN when no luminaire counts
};

// The glare at an eye at `eye` (scene units) looking along `view` (unit; the vertical is +Y),
// from `set`, over background luminance `lb`; `scene` (may be null) hides luminaires.
ObserverGlare observer_glare(const LuminaireSet& set, const RayScene* scene, const Vec3& eye,
                             const Vec3& view, double lb);

} // namespace rad
