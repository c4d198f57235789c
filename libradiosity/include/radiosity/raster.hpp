// A z-buffer rasteriser of the patch mesh with per-corner colours.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"
#include "radiosity/view.hpp"

#include <array>
#include <vector>

namespace rad {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb; // row-major, top row first
    std::size_t covered_pixels = 0;
};

// Perspective-correct interpolation of the corner colours, N x N supersampling per pixel.
Image render(const radfmt::MeshData& mesh, const std::vector<std::array<Rgb, 4>>& corners,
             const View& view, int width, int height, int supersampling);

} // namespace rad
