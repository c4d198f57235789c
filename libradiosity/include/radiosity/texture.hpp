// Textures reduced to what a patch's single reflectance can use: their mean colour.
#pragma once
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

namespace rad {

// Images larger than this many pixels are not decoded (2^26: 8192 x 8192; a 16384^2 PNG
// of under a megabyte costs 1.5 GB and 16 s to decode, for one mean colour).
inline constexpr std::uint64_t kMaxTexturePixels = std::uint64_t(1) << 26;

// The mean colour of an image in linear space (8-bit images are decoded from sRGB first,
// HDR images are linear already), or nothing with `error` set when it cannot be read or has
// more than `max_pixels` pixels (known from its header, before decoding). A file is decoded
// once per run: later calls with the same file (path, size and time unchanged) get the same
// answer from a cache.
std::optional<radfmt::Rgb> mean_texture_colour(const std::filesystem::path& path,
                                               std::string& error,
                                               std::uint64_t max_pixels = kMaxTexturePixels);
// The same for an image held in memory (a texture embedded in a .glb).
std::optional<radfmt::Rgb> mean_texture_colour(std::span<const unsigned char> bytes,
                                               std::string& error,
                                               std::uint64_t max_pixels = kMaxTexturePixels);
// How many images have been decoded in this process (the cache's test).
std::size_t texture_decodes();

} // namespace rad
