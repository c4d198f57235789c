// Baked light out (rad-bake): a solution as a glTF binary, with vertex colours or a lightmap
// atlas (charts of the mesh's surfaces packed into one texture).
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rad {

// A chart: edge-connected patches of one material and group whose normals stay within an angle
// of the first patch's, laid flat by projection onto that patch's plane. A planar region's
// patch grid lies along the chart's axes (u is the first patch's first edge), so it maps
// straight onto texel rows.
struct Chart {
    std::vector<std::uint32_t> patches;
    // Per patch (in `patches` order) and corner: position in the chart's plane, metres,
    // relative to the chart's lower corner (so every coordinate is >= 0).
    std::vector<std::vector<std::array<double, 2>>> corner_uv;
    double width = 0, height = 0; // extent in metres
};
// Every patch lands in exactly one chart; charts come in order of their first patch.
std::vector<Chart> build_charts(const radfmt::MeshData& mesh, double max_angle_deg);

// Where each chart sits in a square atlas: its rectangle (chart plus `padding` texels on each
// side) starts at `origin`, and a chart point (u, v) in metres is texel
// origin + padding + (u, v) * texels_per_metre (texel centres at +0.5).
struct AtlasLayout {
    int size = 0;
    int padding = 0;
    double texels_per_metre = 0;
    std::vector<std::array<int, 2>> origin;
    std::vector<std::array<int, 2>> extent; // rectangle size in texels, padding included
};
// Packs the charts (stb_rect_pack) at `texels_per_metre`, or when that is 0 at the highest
// density that fits. Throws InputError when the charts cannot fit at the density asked for.
AtlasLayout pack_atlas(const std::vector<Chart>& charts, int size, double texels_per_metre,
                       int padding);

// A float RGB atlas; `state` says per texel whether a chart covers its centre (kChart), it is a
// chart rectangle's fill (kPadding: the value of its nearest chart texel), or unused (kEmpty).
// The most memory a --lightmap bake of `size` x `size` texels takes, estimated before it is
// done: each lightmap (the mix, one per light group, the irradiance with --engine) as float RGB
// and a state byte, the chart fill's working arrays, and the files' copies (EXR float layers,
// the PNG's bytes, the glb's PNG images).
std::uint64_t estimate_lightmap_memory(int size, std::size_t light_groups, bool engine, bool exr);

struct Lightmap {
    enum State : std::uint8_t { kEmpty = 0, kChart = 1, kPadding = 2 };
    int size = 0;
    std::vector<float> rgb; // row-major, top row first (glTF's UV origin)
    std::vector<std::uint8_t> state;
};
// Interpolates the corner colours at every texel centre a patch covers, then fills each chart
// rectangle's other texels with the value of their nearest chart texel (8-connected distance),
// so bilinear filtering near a chart's edge never reads another chart or black.
Lightmap render_lightmap(const radfmt::MeshData& mesh, const std::vector<Chart>& charts,
                         const AtlasLayout& layout, const CornerColours& corner_colours);

// Texture coordinate (glTF: 0..1, v down) of each patch corner in the atlas.
std::vector<std::vector<std::array<float, 2>>>
atlas_uv(const radfmt::MeshData& mesh, const std::vector<Chart>& charts, const AtlasLayout& layout);

// Each patch corner's position in its chart, metres (TEXCOORD_0: for tiling textures at a
// known scale; glTF wants a TEXCOORD_0 where there is a TEXCOORD_1).
std::vector<std::vector<std::array<float, 2>>> chart_uv(const radfmt::MeshData& mesh,
                                                        const std::vector<Chart>& charts);

// What goes into a glb. Colours are display values (radiosity times exposure, linear), clamped
// to [0, 1] when written.
struct BakeScene {
    const radfmt::MeshData* mesh = nullptr;
    // Vertex colours (COLOR_0) per patch corner; empty with a lightmap.
    CornerColours corner_colours;
    // With a lightmap: TEXCOORD_0 (chart metres) and TEXCOORD_1 (atlas) per patch corner and
    // the atlas as PNG bytes (sRGB).
    std::vector<std::vector<std::array<float, 2>>> surface_uv, lightmap_uv;
    std::vector<std::uint8_t> lightmap_png;
    // Further lightmaps (one per light group), as PNG bytes, named; the glb lists them in
    // asset.extras.radiosity.light_groups with their image indices.
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> group_lightmaps_png;
    // For engines: materials as the scene's own (metallic-roughness, base colour = reflectance,
    // emission as emissive), not unlit, and the atlas (`lightmap_png`: then irradiance) only
    // listed in asset.extras.radiosity.lightmap, for the engine's lightmap slot.
    bool engine_materials = false;
    double exposure = 1; // for engine materials' emissive display values
    // JSON text of asset.extras.radiosity (provenance and facts).
    std::string extras_json;
    std::string generator;
};
// A binary glTF 2.0 file's bytes: one primitive per material (and per one- or two-sided kind),
// materials KHR_materials_unlit with base colour 1, so viewers show the baked light as it is.
// Throws InputError past a glb's 4 GiB.
std::vector<std::uint8_t> baked_glb(const BakeScene& scene);
// Writes bytes to a file atomically (radfmt::write_atomically); SystemError when it cannot.
void write_file(const std::string& path, const void* data, std::size_t size);

// The viewer page: one HTML file holding the glb (base64), the camera and exposure (a JSON
// object: view {position, direction, up, horizontal_deg, vertical_deg}, exposure) and the
// viewer script (three.js, bundled at build time). Throws InputError when this build has no
// viewer script (web/node_modules was missing when it was built).
std::string viewer_page(const std::vector<std::uint8_t>& glb, const std::string& config_json,
                        const std::string& title);

} // namespace rad

#include "radiosity/smoothing.hpp"

namespace rad {

struct BakeOptions {
    Smoothing smoothing = Smoothing::Crease;
    double crease_deg = 30;
    double exposure = 1;         // display multiplier (rad-shade's), applied to colours and PNGs
    int lightmap_size = 0;       // 0: vertex colours
    double texels_per_metre = 0; // 0: the highest density that fits
    int padding = 2;
    double chart_angle_deg = 20;
    // Also an irradiance atlas for engines (BakeResult::irradiance): needs the solved E and rho.
    const radfmt::MeshData* engine_solved = nullptr;
    // The groups' lightmaps hold signed values (a daylight basis): each is two linear PNGs,
    // "NAME" and "NAME.low", the high and the low byte of 16 bits of 0.5 + 0.5 x value / its
    // scale (BakeResult::group_scales: the largest |value|), not sRGB of value x exposure.
    bool signed_groups = false;
};

struct BakeResult {
    BakeScene scene;    // ready for baked_glb (mesh, colours or lightmap; no extras)
    AtlasLayout layout; // with a lightmap
    std::size_t charts = 0;
    Lightmap lightmap;                        // radiosity, W/m^2 (linear, not exposed)
    std::vector<Lightmap> group_lightmaps;    // one per light group, each at weight 1
    std::vector<double> group_scales;         // signed_groups: each group PNG's scale
    Lightmap irradiance;                      // with engine_solved: W/m^2 falling on the surface
    std::vector<std::uint8_t> irradiance_png; // sRGB of irradiance x exposure
};

// What falls on each patch: H = (B - E) / rho per channel, so that an engine's albedo times H
// (plus emission) gives back B. A channel with rho = 0 takes the mean of the patch's other
// channels' H (0 when it has none).
std::vector<Rgb> patch_irradiance(const radfmt::MeshData& solved,
                                  const std::vector<Rgb>& radiosity);

// Smooths the per-patch radiosity as rad-shade does and lays it out for a glb: vertex colours,
// or charts, atlas and lightmaps (and one lightmap per group when `groups` is not empty).
BakeResult bake(const radfmt::MeshData& mesh, const std::vector<Rgb>& radiosity,
                const std::vector<std::pair<std::string, std::vector<Rgb>>>& groups,
                const BakeOptions& options);

// The lightmap as display pixels: sRGB of radiosity x exposure, 8 bits, top row first.
std::vector<std::uint8_t> lightmap_pixels(const Lightmap& map, double exposure);

} // namespace rad
