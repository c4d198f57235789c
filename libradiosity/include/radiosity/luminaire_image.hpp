// Luminaires in images: each luminous opening drawn where it is in front of the scene, at its
// luminance towards the camera (I / projected area), so a lamp shows as a bright shape, not as
// a hole in the ceiling.
#pragma once
#include "radiosity/luminaires.hpp"
#include "radiosity/raster.hpp"
#include "radiosity/view.hpp"

#include <vector>

namespace rad {

// Replaces the samples (N x N a pixel) that see an opening before any surface with the value
// the image gives a Lambertian surface of that luminance, pi L (W/m^2 through the 179 lm/W
// white), times its group's weight (`group_weights`, per LuminaireSet::groups; empty: 1).
// Openings of no size (a point source) are not drawn. Returns the pixels changed.
std::size_t draw_luminaires(Image& image, const LuminaireSet& set, const RayScene& scene,
                            const View& view, int supersampling,
                            const std::vector<Rgb>& group_weights = {});

} // namespace rad
