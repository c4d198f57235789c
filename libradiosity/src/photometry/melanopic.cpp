#include "radiosity/melanopic.hpp"

#include "radiosity/error.hpp"
#include "radiosity/sensors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

namespace rad {
namespace {

constexpr double kPhotopicEfficacy = 683.002; // lm/W at 555 nm (K_m)

// Which channel (R 0, G 1, B 2) a sample's wavelength falls in, with its share: samples on a
// boundary (490, 580 nm) count half to each side, as a trapezoid over the band would.
constexpr double kBlueGreenNm = 490, kGreenRedNm = 580;
void band_shares(double nm, Rgb& share) {
    share = {0, 0, 0};
    if (nm < kBlueGreenNm)
        share[2] = 1;
    else if (nm == kBlueGreenNm)
        share[2] = share[1] = 0.5;
    else if (nm < kGreenRedNm)
        share[1] = 1;
    else if (nm == kGreenRedNm)
        share[1] = share[0] = 0.5;
    else
        share[0] = 1;
}

double photopic_sum(const Spectrum& s) {
    double sum = 0;
    for (std::size_t k = 0; k < Spectrum::kCount; ++k)
        sum += s.values[k] * photopic_efficiency()[k];
    return sum;
}

// The ratio of melanopic to photopic sums (5 nm steps cancel), per band.
Rgb melanopic_per_photopic_bands(const Spectrum& s) {
    const double photopic = photopic_sum(s);
    if (!(photopic > 0)) throw InputError("spectrum " + s.name + " has no visible light");
    Rgb bands{0, 0, 0}, share;
    for (int k = 0; k < Spectrum::kCount; ++k) {
        band_shares(Spectrum::wavelength(k), share);
        const double m = s.values[std::size_t(k)] * melanopic_action()[std::size_t(k)];
        for (std::size_t c = 0; c < 3; ++c) bands[c] += share[c] * m / photopic;
    }
    return bands;
}

double total(const Rgb& c) {
    return c[0] + c[1] + c[2];
}

} // namespace

double melanopic_elr(const Spectrum& spectrum) {
    return 1000 * total(melanopic_per_photopic_bands(spectrum)) / kPhotopicEfficacy;
}

double melanopic_der(const Spectrum& spectrum) {
    return melanopic_elr(spectrum) / melanopic_elr(cie_d65());
}

Rgb melanopic_der_bands(const Spectrum& spectrum) {
    const double d65 = total(melanopic_per_photopic_bands(cie_d65()));
    auto bands = melanopic_per_photopic_bands(spectrum);
    for (auto& b : bands) b /= d65;
    return bands;
}

Rgb melanopic_weights(const Spectrum& spectrum, const Rgb& tint) {
    const double luminance = luminous(tint);
    if (!(luminance > 0))
        throw InputError("light of spectrum " + spectrum.name + " has no luminous colour");
    const auto bands = melanopic_der_bands(spectrum);
    Rgb w{0, 0, 0};
    for (std::size_t c = 0; c < 3; ++c)
        if (tint[c] > 0) w[c] = kRadianceEfficacy * bands[c] * luminance / tint[c];
    return w;
}

} // namespace rad
