// Luminance pictures as lighting designers read Radiance's falsecolor: an image's luminance
// (cd/m^2) in false colour on a logarithmic scale with a labelled legend, and the luminance of
// each surface the eye sees.
#pragma once
#include "radiosity/raster.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/view.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rad {

// A pixel's luminance (cd/m^2): rad-shade's pixels are radiosity (W/m^2, RGB), whose
// radiance is B/pi, at Radiance's white efficacy of 179 lm/W.
double pixel_luminance(const Image& image, std::size_t pixel);

// The scale from top / 10^decades to top, logarithmic.
struct LuminanceScale {
    double top = 1;
    int decades = 4;
    double bottom() const;
    // Where `luminance` lies on the scale, 0 (at or below the bottom) to 1 (at or above top).
    double position(double luminance) const;
};
// `top` > 0 as given; else the brightest covered pixel rounded up (1, 2, 2.5 or 5 x 10^k).
// Throws InputError when decades is not 1 to 9.
LuminanceScale luminance_scale(const Image& image, double top, int decades);

// The picture: each covered pixel in the false colour of its luminance's place on the scale
// (pixels that see nothing black), a legend beside it labelled in cd/m^2 at 1, 2 and 5 x 10^k
// (or 1 x 10^k where a decade is short), and the scale's range. PNG bytes.
std::vector<std::uint8_t> luminance_png(const Image& image, const LuminanceScale& scale);

// Per material of the surfaces the pixels' centres see, in the order the materials first
// appear in the mesh: how many pixels, their mean and largest luminance (cd/m^2). `image` is
// the view rendered from `view` of `mesh` (the scene `scene` traces).
struct SurfaceLuminance {
    std::string name;
    long pixels = 0;
    double mean = 0, max = 0;
};
std::vector<SurfaceLuminance> surface_luminances(const Image& image, const radfmt::MeshData& mesh,
                                                 const RayScene& scene, const View& view);

} // namespace rad
