// Mean colour of a texture image (stb_image: PNG, JPEG, TGA, BMP, HDR, ...), in linear space.
#include "radiosity/texture.hpp"

// stb_image is a third-party single header: its implementation is compiled here, without
// this project's warning flags.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace rad {

namespace {
double srgb_to_linear(double s) {
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}
} // namespace

namespace {
// Averages stb_image's pixels: float ones are linear (HDR), 8-bit ones sRGB-encoded and
// decoded first (the mean of encoded values would be too dark).
template <class Pixel>
std::optional<radfmt::Rgb> average(Pixel* pixels, int width, int height, bool linear,
                                   std::string& error) {
    if (!pixels) {
        error = stbi_failure_reason();
        return std::nullopt;
    }
    radfmt::Rgb sum{};
    double table[256];
    for (int v = 0; v < 256; ++v) table[v] = srgb_to_linear(v / 255.0);
    for (long i = 0; i < long(width) * height; ++i)
        for (int c = 0; c < 3; ++c) {
            if constexpr (std::is_same_v<Pixel, float>)
                sum[c] += pixels[3 * i + c];
            else
                sum[c] += linear ? pixels[3 * i + c] / 255.0 : table[pixels[3 * i + c]];
        }
    stbi_image_free(pixels);
    const double count = double(width) * height;
    if (!(count > 0)) {
        error = "the image has no pixels";
        return std::nullopt;
    }
    for (int c = 0; c < 3; ++c) sum[c] /= count;
    return sum;
}
} // namespace

std::optional<radfmt::Rgb> mean_texture_colour(const std::filesystem::path& path,
                                               std::string& error) {
    // Loaded first, then averaged: the size is known only once the image is read.
    int width = 0, height = 0, channels = 0;
    const std::string name = path.string();
    if (stbi_is_hdr(name.c_str())) {
        float* pixels = stbi_loadf(name.c_str(), &width, &height, &channels, 3);
        return average(pixels, width, height, true, error);
    }
    unsigned char* pixels = stbi_load(name.c_str(), &width, &height, &channels, 3);
    return average(pixels, width, height, false, error);
}

std::optional<radfmt::Rgb> mean_texture_colour(std::span<const unsigned char> bytes,
                                               std::string& error) {
    int width = 0, height = 0, channels = 0;
    const int size = static_cast<int>(std::min<std::size_t>(bytes.size(), 0x7fffffff));
    if (stbi_is_hdr_from_memory(bytes.data(), size)) {
        float* pixels = stbi_loadf_from_memory(bytes.data(), size, &width, &height, &channels, 3);
        return average(pixels, width, height, true, error);
    }
    unsigned char* pixels =
        stbi_load_from_memory(bytes.data(), size, &width, &height, &channels, 3);
    return average(pixels, width, height, false, error);
}

} // namespace rad
