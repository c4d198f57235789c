// Melanopic light at the eye (CIE S 026:2018): the melanopic equivalent daylight (D65)
// illuminance (melanopic EDI, lx) of light whose source spectrum is known, carried through
// the chain's RGB as three wavelength bands (B 380-490 nm, G 490-580 nm, R 580-780 nm):
// what the room's colours do to each band's share of the light, they do to its melanopic
// content. Exact for rooms of neutral (grey) surfaces; for coloured ones, as exact as three
// bands can be.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/spectrum.hpp"
#include "radiosity/vec.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rad {

// WELL's equivalent melanopic lux (EML, Lucas et al. 2014) in melanopic EDI: EDI = 0.9058 x
// EML (WELL v2 L03), so WELL's M/P ratio is (EDI / Ev) / 0.9058.
inline constexpr double kMelanopicEdiPerEml = 0.9058;

// CIE S 026's melanopic efficacy of luminous radiation (mW/lm) of a spectrum, and its
// melanopic daylight efficacy ratio (mel-DER: its ELR over D65's, 1.3262 mW/lm).
double melanopic_elr(const Spectrum& spectrum);
double melanopic_der(const Spectrum& spectrum);
// mel-DER split by the bands the chain's R, G and B stand for (they add up to mel-DER):
// the melanopic stimulus each band carries per lux of the whole spectrum, D65-equivalent.
Rgb melanopic_der_bands(const Spectrum& spectrum);

// Melanopic EDI (lx) = sum over channels of weights[c] x irradiance[c] (W/m^2, the chain's
// RGB) for light of `spectrum` emitted with the chain colour `tint` (any scale): each band
// arrives at the eye as the share of the source's own band the room passed on. With every
// surface grey it is the illuminance x mel-DER.
Rgb melanopic_weights(const Spectrum& spectrum, const Rgb& tint);
inline double melanopic_edi(const Rgb& irradiance, const Rgb& weights) {
    return weights[0] * irradiance[0] + weights[1] * irradiance[1] + weights[2] * irradiance[2];
}
// The standard error of that sum from each channel's (taken fully correlated: a bound).
inline double melanopic_error(const Rgb& channel_errors, const Rgb& weights) {
    return weights[0] * channel_errors[0] + weights[1] * channel_errors[1] +
           weights[2] * channel_errors[2];
}

// A solution's light sources by spectrum, for melanopic EDI at sensors. Each light group
// takes its spectrum from `specs` ("GROUP=SPEC", or "SPEC" for every group not named; SPEC as
// parse_spectrum), else from its luminaires' lamp colour temperature (a blackbody); a
// solution without groups takes the one "SPEC". Groups of one spectrum and colour share a
// source; when there are several, each is gathered on its own (its emitters, its luminaires
// and its share of the radiosity), so light of each spectrum is weighed by its own bands.
// Throws InputError naming a group with no spectrum to know, an unknown group, or a group of
// luminaires of several colour temperatures.
class MelanopicSources {
  public:
    MelanopicSources(const radfmt::MeshData& mesh, const radfmt::RadiosityData& solution,
                     const radfmt::Header& solution_header, const LuminaireSet* luminaires,
                     const std::vector<std::string>& specs, const GatherOptions& options);
    ~MelanopicSources();

    struct Result {
        double edi = 0, error = 0; // lx; error NaN when not estimated
    };
    // At a sensor whose gather of the whole solution is `whole` (used as it is when one
    // spectrum lights the scene); `index` seeds each source's gather as gather_sensor's.
    Result at(const Irradiance& whole, const Vec3& position, const Vec3& direction,
              std::uint64_t index, const Box& scene_box) const;
    // One line per source: its groups, spectrum and mel-DER.
    std::vector<std::string> describe() const;
    std::size_t sources() const { return sources_.size(); }

  private:
    struct Source;
    std::vector<std::unique_ptr<Source>> sources_;
};

} // namespace rad
