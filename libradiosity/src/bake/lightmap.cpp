// Rendering smoothed radiosity into the atlas: texel centres interpolated inside each patch,
// then each chart's rectangle filled outward from its texels.
#include "radiosity/bake.hpp"
#include "radiosity/patch_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace rad {

namespace {

struct TexelPoint {
    double x, y; // texel coordinates (centres at +0.5)
    Rgb colour;
};

TexelPoint corner_texel(const Chart& chart, std::size_t i, std::size_t k, const AtlasLayout& layout,
                        std::size_t chart_index, const Rgb& colour) {
    const auto& o = layout.origin[chart_index];
    return {o[0] + layout.padding + chart.corner_uv[i][k][0] * layout.texels_per_metre,
            o[1] + layout.padding + chart.corner_uv[i][k][1] * layout.texels_per_metre, colour};
}

void put(Lightmap& map, int x, int y, const Rgb& c, Lightmap::State state) {
    const std::size_t at = std::size_t(y) * map.size + x;
    map.state[at] = state;
    for (int ch = 0; ch < 3; ++ch) map.rgb[3 * at + ch] = static_cast<float>(c[ch]);
}

// Sets the texels whose centres lie in the triangle (not those a chart texel already has);
// returns how many it covers, set or not.
int rasterise_triangle(Lightmap& map, const TexelPoint& a, const TexelPoint& b,
                       const TexelPoint& c) {
    const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::abs(area) < 1e-18) return 0;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(map.size - 1, static_cast<int>(std::floor(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(map.size - 1, static_cast<int>(std::floor(std::max({a.y, b.y, c.y}))));
    const double eps = 1e-9;
    int covered = 0;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const double wa = ((b.x - px) * (c.y - py) - (c.x - px) * (b.y - py)) / area;
            const double wb = ((c.x - px) * (a.y - py) - (a.x - px) * (c.y - py)) / area;
            const double wc = 1 - wa - wb;
            if (wa < -eps || wb < -eps || wc < -eps) continue;
            ++covered;
            if (map.state[std::size_t(y) * map.size + x] == Lightmap::kChart) continue;
            Rgb colour;
            for (int ch = 0; ch < 3; ++ch)
                colour[ch] = a.colour[ch] * wa + b.colour[ch] * wb + c.colour[ch] * wc;
            put(map, x, y, colour, Lightmap::kChart);
        }
    }
    return covered;
}

// Fills the rectangle's other texels from its chart texels, breadth first over 8 neighbours:
// each gets the value of a chart texel at the least Chebyshev distance.
void fill_rectangle(Lightmap& map, const std::array<int, 2>& origin,
                    const std::array<int, 2>& extent) {
    std::deque<std::array<int, 2>> queue;
    for (int y = origin[1]; y < origin[1] + extent[1]; ++y)
        for (int x = origin[0]; x < origin[0] + extent[0]; ++x)
            if (map.state[std::size_t(y) * map.size + x] == Lightmap::kChart)
                queue.push_back({x, y});
    while (!queue.empty()) {
        const auto [x, y] = queue.front();
        queue.pop_front();
        const std::size_t from = std::size_t(y) * map.size + x;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < origin[0] || ny < origin[1] || nx >= origin[0] + extent[0] ||
                    ny >= origin[1] + extent[1])
                    continue;
                const std::size_t to = std::size_t(ny) * map.size + nx;
                if (map.state[to] != Lightmap::kEmpty) continue;
                map.state[to] = Lightmap::kPadding;
                for (int ch = 0; ch < 3; ++ch) map.rgb[3 * to + ch] = map.rgb[3 * from + ch];
                queue.push_back({nx, ny});
            }
        }
    }
}

} // namespace

Lightmap render_lightmap(const radfmt::MeshData& mesh, const std::vector<Chart>& charts,
                         const AtlasLayout& layout, const CornerColours& corner_colours) {
    Lightmap map;
    map.size = layout.size;
    map.rgb.assign(std::size_t(map.size) * map.size * 3, 0.0f);
    map.state.assign(std::size_t(map.size) * map.size, Lightmap::kEmpty);
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const Chart& chart = charts[c];
        for (std::size_t i = 0; i < chart.patches.size(); ++i) {
            const auto patch = chart.patches[i];
            const auto n = mesh.corners(patch).size();
            std::vector<TexelPoint> t(n);
            for (std::size_t k = 0; k < n; ++k)
                t[k] = corner_texel(chart, i, k, layout, c, corner_colours.at(mesh, patch, k));
            // As rad-shade draws a quad or polygon: its fan of triangles from corner 0.
            int covered = 0;
            for (const auto& [a, b, d] : patch_triangles(mesh, patch))
                covered += rasterise_triangle(map, t[a], t[b], t[d]);
            if (covered > 0) continue;
            // A patch thinner than a texel: its centre's texel carries it.
            TexelPoint mid{0, 0, {}};
            for (std::size_t k = 0; k < n; ++k) {
                mid.x += t[k].x / n;
                mid.y += t[k].y / n;
                for (int ch = 0; ch < 3; ++ch) mid.colour[ch] += t[k].colour[ch] / n;
            }
            const int x = std::clamp(static_cast<int>(mid.x), 0, map.size - 1);
            const int y = std::clamp(static_cast<int>(mid.y), 0, map.size - 1);
            if (map.state[std::size_t(y) * map.size + x] != Lightmap::kChart)
                put(map, x, y, mid.colour, Lightmap::kChart);
        }
    }
    for (std::size_t c = 0; c < charts.size(); ++c)
        fill_rectangle(map, layout.origin[c], layout.extent[c]);
    return map;
}

std::vector<std::vector<std::array<float, 2>>> atlas_uv(const radfmt::MeshData& mesh,
                                                        const std::vector<Chart>& charts,
                                                        const AtlasLayout& layout) {
    std::vector<std::vector<std::array<float, 2>>> uv(mesh.patches.size());
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const Chart& chart = charts[c];
        for (std::size_t i = 0; i < chart.patches.size(); ++i) {
            const auto patch = chart.patches[i];
            uv[patch].resize(mesh.corners(patch).size());
            for (std::size_t k = 0; k < uv[patch].size(); ++k) {
                const auto t = corner_texel(chart, i, k, layout, c, Rgb{});
                uv[patch][k] = {static_cast<float>(t.x / layout.size),
                                static_cast<float>(t.y / layout.size)};
            }
        }
    }
    return uv;
}

std::vector<std::vector<std::array<float, 2>>> chart_uv(const radfmt::MeshData& mesh,
                                                        const std::vector<Chart>& charts) {
    std::vector<std::vector<std::array<float, 2>>> uv(mesh.patches.size());
    for (const Chart& chart : charts)
        for (std::size_t i = 0; i < chart.patches.size(); ++i)
            for (const auto& [u, v] : chart.corner_uv[i])
                uv[chart.patches[i]].push_back({static_cast<float>(u), static_cast<float>(v)});
    return uv;
}

std::uint64_t estimate_lightmap_memory(int size, std::size_t light_groups, bool engine, bool exr) {
    const std::uint64_t texels = std::uint64_t(size) * std::uint64_t(size);
    const std::uint64_t maps = 1 + light_groups + (engine ? 1 : 0);
    std::uint64_t per_texel = maps * 13 + 16; // RGB floats and state, the fill's arrays
    per_texel += maps * 4;                    // the glb's images (RGBA8) as they are encoded
    if (exr) per_texel += maps * 12;          // the EXR's float layers
    return texels * per_texel;
}

} // namespace rad
