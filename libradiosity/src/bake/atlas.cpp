// Packing charts into a square atlas with stb_rect_pack, at a given or the highest density.
#include "radiosity/bake.hpp"
#include "radiosity/error.hpp"

// stb_rect_pack is a third-party single header: its implementation is compiled here, without
// this project's warning flags.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wshadow"
#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>
#pragma GCC diagnostic pop

#include <cmath>
#include <string>

namespace rad {

namespace {

// Rectangle of a chart in texels: its extent rounded up, plus a texel for the partly covered
// edge, plus padding both sides.
std::array<int, 2> chart_extent(const Chart& chart, double density, int padding) {
    const auto texels = [&](double metres) {
        return static_cast<int>(std::ceil(metres * density)) + 1 + 2 * padding;
    };
    return {texels(chart.width), texels(chart.height)};
}

// Packs at one density; false when some chart does not fit.
bool try_pack(const std::vector<Chart>& charts, int size, double density, int padding,
              AtlasLayout& layout) {
    std::vector<stbrp_rect> rects(charts.size());
    for (std::size_t i = 0; i < charts.size(); ++i) {
        const double w = charts[i].width * density, h = charts[i].height * density;
        if (!(w < size && h < size)) return false;
        const auto extent = chart_extent(charts[i], density, padding);
        if (extent[0] > size || extent[1] > size) return false;
        rects[i] = stbrp_rect{static_cast<int>(i), extent[0], extent[1], 0, 0, 0};
    }
    std::vector<stbrp_node> nodes(static_cast<std::size_t>(size));
    stbrp_context context;
    stbrp_init_target(&context, size, size, nodes.data(), size);
    if (!stbrp_pack_rects(&context, rects.data(), static_cast<int>(rects.size()))) return false;
    layout.size = size;
    layout.padding = padding;
    layout.texels_per_metre = density;
    layout.origin.resize(charts.size());
    layout.extent.resize(charts.size());
    for (const auto& r : rects) {
        layout.origin[static_cast<std::size_t>(r.id)] = {r.x, r.y};
        layout.extent[static_cast<std::size_t>(r.id)] = {r.w, r.h};
    }
    return true;
}

} // namespace

AtlasLayout pack_atlas(const std::vector<Chart>& charts, int size, double texels_per_metre,
                       int padding) {
    if (size < 8 || size > 16384) throw InputError("lightmap size must be 8 to 16384 texels");
    AtlasLayout layout;
    if (texels_per_metre > 0) {
        if (!try_pack(charts, size, texels_per_metre, padding, layout))
            throw InputError("the charts do not fit a " + std::to_string(size) + "x" +
                             std::to_string(size) + " lightmap at " +
                             std::to_string(texels_per_metre) +
                             " texels per metre (use fewer texels per metre or a larger size)");
        return layout;
    }
    // Start where the charts' area alone would fill the atlas and step down 3% at a time:
    // the first density that packs is within 3% of the best this packer finds.
    double area = 0;
    for (const auto& c : charts) area += std::max(c.width * c.height, 1e-12);
    double density = std::sqrt(double(size) * size / area);
    for (int step = 0; step < 400; ++step, density *= 0.97)
        if (try_pack(charts, size, density, padding, layout)) return layout;
    throw InputError("the mesh's " + std::to_string(charts.size()) + " charts do not fit a " +
                     std::to_string(size) + "x" + std::to_string(size) +
                     " lightmap even at a texel a chart (use a larger size, or vertex colours)");
}

} // namespace rad
