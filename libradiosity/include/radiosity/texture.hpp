// Textures reduced to what a patch's single reflectance can use: their mean colour.
#pragma once
#include "radfmt/kinds.hpp"

#include <filesystem>
#include <optional>
#include <span>
#include <string>

namespace rad {

// The mean colour of an image in linear space (8-bit images are decoded from sRGB first,
// HDR images are linear already), or nothing with `error` set when it cannot be read.
std::optional<radfmt::Rgb> mean_texture_colour(const std::filesystem::path& path,
                                               std::string& error);
// The same for an image held in memory (a texture embedded in a .glb).
std::optional<radfmt::Rgb> mean_texture_colour(std::span<const unsigned char> bytes,
                                               std::string& error);

} // namespace rad
