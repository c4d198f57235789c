// Bands of rad-shade's image: parts written as OpenEXR, merged into one run's image.
#include "radiosity/image_parts.hpp"

#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/image_io.hpp"
#include "radiosity/numbers.hpp"

#include <algorithm>
#include <cstdio>

namespace rad {

namespace {
// The layer with each pixel's back-face share (R) and coverage (G).
constexpr const char* kPartLayer = "radiosity-part";
constexpr const char* kRows = "radiosity:part-rows";
constexpr const char* kExposure = "radiosity:part-exposure";
constexpr const char* kBackfaces = "radiosity:part-backfaces";
constexpr const char* kPng = "radiosity:part-png";
constexpr const char* kProvenance = "radiosity:provenance";

bool part_only(const std::string& key) {
    return key.rfind("radiosity:part-", 0) == 0;
}

const std::string& attribute(const std::map<std::string, std::string>& attributes, const char* key,
                             const std::string& path) {
    const auto it = attributes.find(key);
    if (it == attributes.end())
        throw InputError(path + ": no " + key + " attribute: not a part from rad-shade --rows");
    return it->second;
}

// "A:B of H".
RowBand parse_band(const std::string& text, const std::string& path, int& height) {
    int begin = 0, end = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d:%d of %d%c", &begin, &end, &height, &tail) != 3 ||
        !(0 <= begin && begin < end && end <= height))
        throw InputError(path + ": " + kRows + " '" + text + "' is not 'A:B of HEIGHT'");
    return {begin, end};
}

struct ReadPart {
    std::string path;
    Image image, layer;
    std::map<std::string, std::string> attributes;
    RowBand band;
    int height = 0;
};
} // namespace

void keep_rows(Image& image, RowBand band) {
    const int begin = std::clamp(band.begin, 0, image.height);
    const int end = band.end < 0 ? image.height : std::clamp(band.end, begin, image.height);
    const std::size_t w = std::size_t(image.width);
    if (image.covered.size() != w * std::size_t(image.height))
        throw InternalError("keep_rows: the image has no per-pixel coverage");
    image.covered_pixels = image.back_face_pixels = 0;
    for (int y = 0; y < image.height; ++y)
        for (std::size_t x = 0; x < w; ++x) {
            const std::size_t at = std::size_t(y) * w + x;
            if (y < begin || y >= end) {
                std::fill_n(image.rgb.begin() + long(3 * at), 3, 0.0f);
                image.back_coverage[at] = 0;
                image.covered[at] = 0;
            }
            image.covered_pixels += image.covered[at];
            image.back_face_pixels += image.back_coverage[at] >= 0.5f;
        }
}

void write_image_part(const std::string& path, const Image& band_image, const ImagePartInfo& info) {
    auto attributes = info.attributes;
    attributes[kRows] = std::to_string(info.band.begin) + ":" + std::to_string(info.band.end) +
                        " of " + std::to_string(band_image.height);
    char exposure[40];
    std::snprintf(exposure, sizeof exposure, "%.17g", info.exposure);
    attributes[kExposure] = exposure;
    attributes[kBackfaces] = info.mark_backs ? "mark" : "show";
    attributes[kPng] = info.png;
    Image layer;
    layer.width = band_image.width;
    layer.height = band_image.height;
    layer.rgb.assign(band_image.rgb.size(), 0.0f);
    for (std::size_t p = 0; p < band_image.covered.size(); ++p) {
        layer.rgb[3 * p] = band_image.back_coverage[p];
        layer.rgb[3 * p + 1] = band_image.covered[p];
    }
    write_exr(path, band_image, attributes, {{kPartLayer, &layer}});
}

MergedImage merge_image_parts(const std::vector<std::string>& paths, const std::string& output) {
    if (paths.empty()) throw InputError("--merge needs the part files to merge");
    std::vector<ReadPart> parts;
    std::vector<RowPart> cover;
    for (const auto& path : paths) {
        ReadPart part{path, {}, {}, {}, {}, 0};
        part.image = read_exr(path, &part.attributes);
        part.band = parse_band(attribute(part.attributes, kRows, path), path, part.height);
        part.layer = read_exr_layer(path, kPartLayer);
        if (part.image.height != part.height)
            throw InputError(path + ": " + std::to_string(part.image.height) +
                             " rows, its attribute says " + std::to_string(part.height));
        cover.push_back({path, std::uint64_t(part.band.begin), std::uint64_t(part.band.end)});
        parts.push_back(std::move(part));
    }
    const auto& first = parts.front();
    for (const auto& p : parts) {
        auto same = p.image.width == first.image.width && p.height == first.height &&
                    p.attributes.size() == first.attributes.size();
        for (const auto& [key, value] : first.attributes)
            if (same && key != kRows) {
                const auto it = p.attributes.find(key);
                same = it != p.attributes.end() && it->second == value;
            }
        if (!same)
            throw InputError(p.path + " and " + first.path +
                             " are parts of different images (other inputs, camera, size or "
                             "options): render every part with one command");
    }
    require_row_cover(cover, std::uint64_t(first.height));

    MergedImage merged;
    Image& image = merged.image;
    image.width = first.image.width;
    image.height = first.height;
    const std::size_t w = std::size_t(image.width), pixels = w * std::size_t(image.height);
    image.rgb.assign(3 * pixels, 0.0f);
    image.back_coverage.assign(pixels, 0.0f);
    image.covered.assign(pixels, 0);
    for (const auto& p : parts)
        for (std::size_t at = std::size_t(p.band.begin) * w; at < std::size_t(p.band.end) * w;
             ++at) {
            std::copy_n(p.image.rgb.begin() + long(3 * at), 3, image.rgb.begin() + long(3 * at));
            image.back_coverage[at] = p.layer.rgb[3 * at];
            image.covered[at] = p.layer.rgb[3 * at + 1] > 0.5f;
            image.covered_pixels += image.covered[at];
            image.back_face_pixels += image.back_coverage[at] >= 0.5f;
        }

    auto& info = merged.info;
    info.band = {0, image.height};
    if (!parse_number(attribute(first.attributes, kExposure, first.path), info.exposure))
        throw InputError(first.path + ": " + kExposure + " is not a number");
    info.mark_backs = attribute(first.attributes, kBackfaces, first.path) == "mark";
    info.png = attribute(first.attributes, kPng, first.path);
    for (const auto& [key, value] : first.attributes)
        if (!part_only(key)) info.attributes[key] = value;
    // The provenance's last line is the command one run would have had.
    attribute(info.attributes, kProvenance, first.path);
    auto& provenance = info.attributes[kProvenance];
    provenance = command_with_output(provenance, output, first.path);
    return merged;
}

} // namespace rad
