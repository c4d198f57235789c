// From a solution to what a glb holds: smoothed corner colours, or charts and lightmaps.
#include "radiosity/bake.hpp"
#include "radiosity/image_io.hpp"

#include <algorithm>
#include <cmath>

namespace rad {

std::vector<std::uint8_t> lightmap_pixels(const Lightmap& map, double exposure) {
    std::vector<std::uint8_t> pixels(map.rgb.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = to_srgb8(map.rgb[i] * exposure);
    return pixels;
}

std::vector<Rgb> patch_irradiance(const radfmt::MeshData& solved,
                                  const std::vector<Rgb>& radiosity) {
    std::vector<Rgb> h(radiosity.size());
    for (std::size_t i = 0; i < h.size(); ++i) {
        const auto& m = solved.materials[solved.patches[i].material];
        double sum = 0;
        int known = 0;
        for (int c = 0; c < 3; ++c)
            if (m.reflectance[c] > 0) {
                h[i][c] = std::max(0.0, radiosity[i][c] - m.emission[c]) / m.reflectance[c];
                sum += h[i][c];
                ++known;
            }
        for (int c = 0; c < 3; ++c)
            if (!(m.reflectance[c] > 0)) h[i][c] = known > 0 ? sum / known : 0;
    }
    return h;
}

namespace {
// A signed group's lightmap in 16 bits, as two PNGs (the high and the low byte of 0.5 + 0.5 x
// value / scale, scale the largest |value|): a daylight basis's weights cancel each other, and
// the sun's patch lights the floor a hundred times as much as the walls, so 8 bits would show
// as blotches on the walls.
void add_signed_lightmap(const std::string& name, const Lightmap& map, BakeResult& result) {
    double scale = 0;
    for (const float v : map.rgb) scale = std::max(scale, double(std::abs(v)));
    if (!(scale > 0)) scale = 1;
    std::vector<std::uint8_t> high(map.rgb.size()), low(map.rgb.size());
    for (std::size_t i = 0; i < map.rgb.size(); ++i) {
        const double unit = std::clamp(0.5 + 0.5 * map.rgb[i] / scale, 0.0, 1.0);
        const auto q = static_cast<std::uint32_t>(std::lround(unit * 65535));
        high[i] = std::uint8_t(q >> 8);
        low[i] = std::uint8_t(q & 255);
    }
    result.group_scales.push_back(scale);
    auto& pngs = result.scene.group_lightmaps_png;
    pngs.emplace_back(name, encode_png_rgb8(map.size, map.size, high));
    pngs.emplace_back(name + ".low", encode_png_rgb8(map.size, map.size, low));
}
} // namespace

BakeResult bake(const radfmt::MeshData& mesh, const std::vector<Rgb>& radiosity,
                const std::vector<std::pair<std::string, std::vector<Rgb>>>& groups,
                const BakeOptions& options) {
    BakeResult result;
    result.scene.mesh = &mesh;
    auto corners = corner_colours(mesh, radiosity, options.smoothing, options.crease_deg);
    if (options.lightmap_size == 0) {
        for (auto& patch : corners.patches)
            for (auto& c : patch)
                for (auto& channel : c) channel *= options.exposure;
        for (auto& c : corners.polygon_corners)
            for (auto& channel : c) channel *= options.exposure;
        result.scene.corner_colours = std::move(corners);
        return result;
    }
    const auto charts = build_charts(mesh, options.chart_angle_deg);
    result.charts = charts.size();
    result.layout =
        pack_atlas(charts, options.lightmap_size, options.texels_per_metre, options.padding);
    result.lightmap = render_lightmap(mesh, charts, result.layout, corners);
    result.scene.lightmap_uv = atlas_uv(mesh, charts, result.layout);
    result.scene.surface_uv = chart_uv(mesh, charts);
    const int size = result.layout.size;
    result.scene.lightmap_png =
        encode_png_rgb8(size, size, lightmap_pixels(result.lightmap, options.exposure));
    if (options.engine_solved) {
        const auto irradiance = patch_irradiance(*options.engine_solved, radiosity);
        result.irradiance = render_lightmap(
            mesh, charts, result.layout,
            corner_colours(mesh, irradiance, options.smoothing, options.crease_deg));
        result.irradiance_png =
            encode_png_rgb8(size, size, lightmap_pixels(result.irradiance, options.exposure));
    }
    for (const auto& [name, values] : groups) {
        const auto group_corners =
            corner_colours(mesh, values, options.smoothing, options.crease_deg);
        result.group_lightmaps.push_back(
            render_lightmap(mesh, charts, result.layout, group_corners));
        const auto& map = result.group_lightmaps.back();
        if (!options.signed_groups) {
            result.scene.group_lightmaps_png.emplace_back(
                name, encode_png_rgb8(size, size, lightmap_pixels(map, options.exposure)));
            continue;
        }
        add_signed_lightmap(name, map, result);
    }
    return result;
}

} // namespace rad
