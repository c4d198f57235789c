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
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>
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

namespace {
std::atomic<std::size_t> decodes{0};

// Refuses an image whose header gives more than `max_pixels` pixels.
bool within_limit(int width, int height, std::uint64_t max_pixels, std::string& error) {
    const auto pixels = std::uint64_t(std::max(width, 0)) * std::uint64_t(std::max(height, 0));
    if (pixels <= max_pixels) return true;
    error = std::to_string(width) + " x " + std::to_string(height) + " pixels, over the limit of " +
            std::to_string(max_pixels) + " (--max-texture-pixels raises it)";
    return false;
}

std::optional<radfmt::Rgb> decode_mean(const std::string& name, std::string& error,
                                       std::uint64_t max_pixels) {
    int width = 0, height = 0, channels = 0;
    if (stbi_info(name.c_str(), &width, &height, &channels) &&
        !within_limit(width, height, max_pixels, error))
        return std::nullopt;
    ++decodes;
    if (stbi_is_hdr(name.c_str())) {
        float* pixels = stbi_loadf(name.c_str(), &width, &height, &channels, 3);
        return average(pixels, width, height, true, error);
    }
    unsigned char* pixels = stbi_load(name.c_str(), &width, &height, &channels, 3);
    return average(pixels, width, height, false, error);
}

// Answers by file: its canonical path, size and modification time, and the limit asked.
struct CachedMean {
    std::optional<radfmt::Rgb> mean;
    std::string error;
};
using CacheKey = std::tuple<std::string, std::uintmax_t, std::int64_t, std::uint64_t>;
std::mutex cache_mutex;
std::map<CacheKey, CachedMean> cache;
} // namespace

std::size_t texture_decodes() {
    return decodes.load();
}

std::optional<radfmt::Rgb> mean_texture_colour(const std::filesystem::path& path,
                                               std::string& error, std::uint64_t max_pixels) {
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(path, ec);
    const auto size = std::filesystem::file_size(path, ec);
    const auto time = std::filesystem::last_write_time(path, ec);
    if (ec) return decode_mean(path.string(), error, max_pixels);
    const CacheKey key{canonical.string(), size, std::int64_t(time.time_since_epoch().count()),
                       max_pixels};
    {
        std::lock_guard lock(cache_mutex);
        if (const auto it = cache.find(key); it != cache.end()) {
            error = it->second.error;
            return it->second.mean;
        }
    }
    CachedMean answer;
    answer.mean = decode_mean(path.string(), answer.error, max_pixels);
    std::lock_guard lock(cache_mutex);
    cache.emplace(key, answer);
    error = answer.error;
    return answer.mean;
}

std::optional<radfmt::Rgb> mean_texture_colour(std::span<const unsigned char> bytes,
                                               std::string& error, std::uint64_t max_pixels) {
    int width = 0, height = 0, channels = 0;
    const int size = static_cast<int>(std::min<std::size_t>(bytes.size(), 0x7fffffff));
    if (stbi_info_from_memory(bytes.data(), size, &width, &height, &channels) &&
        !within_limit(width, height, max_pixels, error))
        return std::nullopt;
    ++decodes;
    if (stbi_is_hdr_from_memory(bytes.data(), size)) {
        float* pixels = stbi_loadf_from_memory(bytes.data(), size, &width, &height, &channels, 3);
        return average(pixels, width, height, true, error);
    }
    unsigned char* pixels =
        stbi_load_from_memory(bytes.data(), size, &width, &height, &channels, 3);
    return average(pixels, width, height, false, error);
}

} // namespace rad
