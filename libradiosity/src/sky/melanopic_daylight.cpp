// The daylight options that weigh the RGB bands for melanopic EDI instead of lux.
#include "radiosity/daylight.hpp"
#include "radiosity/melanopic.hpp"

namespace rad {

DaylightOptions melanopic_daylight_options(DaylightOptions options, const Spectrum& spectrum) {
    // Per unit of white light, band c carries mel-DER_c of melanopic EDI per lux: with grey
    // surfaces and glass the sum, mel-DER, as CIE S 026 has it for the whole spectrum.
    options.channel_weights = melanopic_der_bands(spectrum);
    options.beam_weight = melanopic_der(spectrum);
    return options;
}

} // namespace rad
