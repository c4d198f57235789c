// A z-buffer rasteriser of the patch mesh with per-corner colours.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/vec.hpp"
#include "radiosity/view.hpp"

#include <array>
#include <vector>

namespace rad {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb; // row-major, top row first
    std::size_t covered_pixels = 0;
    // Per pixel, the share of its samples that show the back of a one-sided patch (a face
    // seen from the side that gets no light), and the pixels where that is at least half.
    std::vector<float> back_coverage;
    std::size_t back_face_pixels = 0;
    std::vector<std::uint8_t> covered; // per pixel: 1 where a sample sees geometry
    // A final gather's per-pixel standard error (RGB, the image's units; empty when none):
    // what the gather's sampling leaves uncertain in each pixel (rad-shade --error-layer).
    std::vector<float> error;
    // An irradiance cache's records, and the samples no record covered (a pixel's on one
    // patch shared a gather of their own, as a record's).
    std::size_t cache_records = 0;
    long uncached_samples = 0;
};

// Image rows [begin, end) (end -1: to the bottom): a band of an image, rad-shade --rows.
struct RowBand {
    int begin = 0, end = -1;
};

// Perspective-correct interpolation of the corner colours, N x N supersampling per pixel.
// Of a two-sided surface (two patches on one spot facing away from each other) each pixel
// shows the side that faces the camera.
// The most memory one run of rad-shade takes for images of this size: the supersampled
// buffers of one render (colour, depth, back-face mark: 21 bytes a sample), and per
// finished image (the main one and one per layer) its RGB, back coverage and coverage plus the
// writers' copies (EXR, PNG).
std::uint64_t estimate_render_memory(int width, int height, int supersampling, int images);

// A mesh with mirrors or glass is drawn by render_specular instead (rays from the camera
// that go on through them, specular_view.hpp), with the same colours.
Image render(const radfmt::MeshData& mesh, const CornerColours& corners, const View& view,
             int width, int height, int supersampling);

// Paints the pixels that mostly show back faces in `colour` (rad-shade --backfaces mark).
void mark_back_faces(Image& image, const Rgb& colour);

} // namespace rad
