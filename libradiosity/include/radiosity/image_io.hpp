// Image and mesh output: linear OpenEXR with attributes, sRGB PNG, vertex-coloured PLY.
#pragma once
#include "radiosity/raster.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rad {

// Extra layers (same size as the image) are written as channels "<name>.R/G/B" next to the
// main R, G, B: the multi-layer convention compositing tools read.
struct ImageLayer {
    std::string name;
    const Image* image;
};
void write_exr(const std::string& path, const Image& image,
               const std::map<std::string, std::string>& attributes,
               const std::vector<ImageLayer>& layers = {});
// Reads a layer's channels ("" for the main R, G, B).
Image read_exr_layer(const std::string& path, const std::string& layer,
                     std::map<std::string, std::string>* attributes = nullptr);
Image read_exr(const std::string& path, std::map<std::string, std::string>* attributes = nullptr);
// Multiplier that maps the 95th-percentile luminance of covered pixels to 0.8.
double auto_exposure(const Image& image);
// Exposure from a solution, the same for every view of it: 0.85 over the luminance that 99% of
// the area of the surfaces that do not emit stays below (emitters in view are not what the
// picture is exposed for); when nothing that does not emit is lit, the same over the
// emitters. 0 when nothing is lit.
double solution_exposure(const radfmt::MeshData& solved, const std::vector<Rgb>& radiosity);
void write_png(const std::string& path, const Image& image, double exposure);
// 8-bit sRGB pixels, row-major, top row first, 3 bytes each.
void write_png_rgb8(const std::string& path, int width, int height,
                    const std::vector<std::uint8_t>& pixels);
// The same PNG as bytes in memory (for a glb's embedded images).
std::vector<std::uint8_t> encode_png_rgb8(int width, int height,
                                          const std::vector<std::uint8_t>& pixels);
void write_ply(const std::string& path, const radfmt::MeshData& mesh, const CornerColours& corners,
               double exposure);
std::uint8_t to_srgb8(double linear);

} // namespace rad
