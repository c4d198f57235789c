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

#include <cmath>

namespace rad {

namespace {
double srgb_to_linear(double s) {
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}
} // namespace

std::optional<radfmt::Rgb> mean_texture_colour(const std::filesystem::path& path,
                                               std::string& error) {
    int width = 0, height = 0, channels = 0;
    radfmt::Rgb sum{};
    const std::string name = path.string();
    if (stbi_is_hdr(name.c_str())) {
        // Radiance HDR and the like hold linear values already.
        float* pixels = stbi_loadf(name.c_str(), &width, &height, &channels, 3);
        if (!pixels) {
            error = stbi_failure_reason();
            return std::nullopt;
        }
        for (long i = 0; i < long(width) * height; ++i)
            for (int c = 0; c < 3; ++c) sum[c] += pixels[3 * i + c];
        stbi_image_free(pixels);
    } else {
        // 8-bit images are sRGB-encoded: decode each pixel before averaging (the mean of
        // encoded values would be too dark).
        unsigned char* pixels = stbi_load(name.c_str(), &width, &height, &channels, 3);
        if (!pixels) {
            error = stbi_failure_reason();
            return std::nullopt;
        }
        double table[256];
        for (int v = 0; v < 256; ++v) table[v] = srgb_to_linear(v / 255.0);
        for (long i = 0; i < long(width) * height; ++i)
            for (int c = 0; c < 3; ++c) sum[c] += table[pixels[3 * i + c]];
        stbi_image_free(pixels);
    }
    const double count = double(width) * height;
    if (!(count > 0)) {
        error = "the image has no pixels";
        return std::nullopt;
    }
    for (int c = 0; c < 3; ++c) sum[c] /= count;
    return sum;
}

} // namespace rad
