// Pass 2 of the two-pass method: images of a mesh with mirrors and glass. Each sample's ray
// from the camera goes on through mirrors and glass (rad::follow_specular), and every surface
// it reaches adds its colour times the share of light that comes along the path: a mirror
// shows the room, glass refracts it, both show the lamps' highlights.
#pragma once
#include "radiosity/raster.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/view.hpp"

#include <functional>

namespace rad {

// A surface's colour where a path reached its front (`sample`: the sample's index, a seed);
// with `error`, the colour's standard error there too (0 for an exact one).
using HitShader = std::function<Rgb(const PathHit& hit, std::uint64_t sample, Rgb* error)>;

struct SpecularView {
    const radfmt::MeshData& mesh;
    const RayScene& scene;
    const SpecularSurfaces& surfaces;
    int depth = kDefaultSpecularDepth;
};

// The same camera, pixel convention, supersampling and row bands as render(); the pixels a
// sample's first surface shows from behind are counted in back_coverage (glass excepted). Of
// a two-sided pair the side facing the camera is shown. With `errors`, Image::error holds each
// pixel's standard error from the shader's: the surfaces a path reaches are shaded from
// their own streams, so their errors add in quadrature, each times the path's weight, and the
// samples' in quadrature over their count.
Image render_specular(const SpecularView& scene, const View& view, int width, int height,
                      int supersampling, const HitShader& shade, bool quiet, RowBand rows = {},
                      bool errors = false);

// render()'s colours for render_specular: the corner colours interpolated where a path met
// a patch.
HitShader smoothed_shader(const radfmt::MeshData& mesh, const CornerColours& corners);

struct SharpBeam;
// render() of a daylight solution under a sky with the sun's beam sharp (radiosity/daylight.hpp:
// `corners` smoothed from beam.radiosity): every surface a path meets shows its corner colours
// plus the beam's light at the point it was met (traced to the sun, through glass). `mesh`
// gives the reflectances (as solved).
Image render_with_beam(const radfmt::MeshData& mesh, const CornerColours& corners,
                       const SharpBeam& beam, const View& view, int width, int height,
                       int supersampling, bool quiet, RowBand rows = {});

} // namespace rad
