// rad-shade --gather: images whose every sample is a final gather at the visible point,
// E + rho x (irradiance gathered there), instead of the patches' interpolated radiosity:
// shadows as sharp as the geometry, no blotches from noisy form factors.
#pragma once
#include "radiosity/gather.hpp"
#include "radiosity/irradiance_cache.hpp"
#include "radiosity/raster.hpp"
#include "radiosity/view.hpp"

namespace rad {
struct LuminaireSet;

// Same camera and pixel convention as render(); N x N samples per pixel, each seeded by
// its index, so the image is the same at any thread count.
// `luminaires` (a solve's rad-solve --direct): their direct light is added exactly at each
// visible point. Only the image rows in `rows` are gathered (the rest stay black and
// uncovered): a band for rad-shade --rows, the same pixels a whole run gives there.
// `cache`: the indirect light from an irradiance cache (irradiance_cache.hpp) instead of
// every sample's rays; null: every sample gathers all its rays (and the image has the error
// layer). Not for meshes with mirrors or glass, which always gather in full.
Image render_gathered(const Gatherer& gatherer, const View& view, int width, int height,
                      int supersampling, bool quiet, const LuminaireSet* luminaires = nullptr,
                      RowBand rows = {}, const IrradianceCacheOptions* cache = nullptr);

} // namespace rad
