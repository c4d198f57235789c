// Luminance in false colour on a logarithmic scale, and per surface seen.
#include "radiosity/luminance_map.hpp"

#include "radiosity/error.hpp"
#include "radiosity/falsecolour.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/image_io.hpp"
#include "shade/canvas.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace rad {
namespace {

std::string label(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// The legend: a bar from the bottom (low) to the top, ticks at 1, 2, 5 x 10^k.
void draw_legend(image_canvas::Canvas& canvas, int x, int y, int height,
                 const LuminanceScale& scale) {
    for (int row = 0; row < height; ++row)
        canvas.fill(x, y + row, x + 24, y + row + 1, false_colour(1 - (row + 0.5) / height));
    const double per_decade = double(height) / scale.decades;
    const int first = int(std::floor(std::log10(scale.bottom()) + 1e-9));
    for (int k = first; k <= first + scale.decades + 1; ++k)
        for (const double m : {1.0, 2.0, 5.0}) {
            if (m != 1 && per_decade < 54) continue; // too close to label
            const double value = m * std::pow(10.0, k);
            if (value < scale.bottom() * (1 - 1e-9) || value > scale.top * (1 + 1e-9)) continue;
            const int at = y + height - int(std::lround(scale.position(value) * height));
            canvas.fill(x + 24, at - 1, x + 32, at + 1, {0, 0, 0});
            canvas.text(x + 36, at - 6, label(value));
        }
    canvas.text(x, y + height + 10, "cd/m2 (log)");
}

} // namespace

double pixel_luminance(const Image& image, std::size_t pixel) {
    const Rgb radiosity{image.rgb[3 * pixel], image.rgb[3 * pixel + 1], image.rgb[3 * pixel + 2]};
    return kRadianceEfficacy * luminous(radiosity) / std::numbers::pi;
}

double LuminanceScale::bottom() const {
    return top / std::pow(10.0, decades);
}

double LuminanceScale::position(double luminance) const {
    if (!(luminance > bottom())) return 0;
    return std::min(1.0, std::log10(luminance / bottom()) / decades);
}

LuminanceScale luminance_scale(const Image& image, double top, int decades) {
    if (decades < 1 || decades > 9)
        throw InputError("--falsecolor-decades " + std::to_string(decades) +
                         ": give 1 to 9 decades below the top");
    double brightest = 0;
    for (std::size_t p = 0; p < image.covered.size(); ++p)
        if (image.covered[p]) brightest = std::max(brightest, pixel_luminance(image, p));
    return {top > 0 ? top : false_colour_top(brightest), decades};
}

std::vector<std::uint8_t> luminance_png(const Image& image, const LuminanceScale& scale) {
    const int margin = 12, legend_w = 150, legend_h = 240;
    image_canvas::Canvas canvas(image.width + margin + legend_w,
                                std::max(image.height, legend_h + 60));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto p = std::size_t(y) * image.width + x;
            const bool seen = p < image.covered.size() && image.covered[p];
            canvas.fill(x, y, x + 1, y + 1,
                        seen ? false_colour(scale.position(pixel_luminance(image, p)))
                             : std::array<std::uint8_t, 3>{0, 0, 0});
        }
    draw_legend(canvas, image.width + margin, 20, legend_h, scale);
    return encode_png_rgb8(canvas.width, canvas.height, canvas.pixels);
}

std::vector<SurfaceLuminance> surface_luminances(const Image& image, const radfmt::MeshData& mesh,
                                                 const RayScene& scene, const View& view) {
    std::vector<SurfaceLuminance> per_material(mesh.materials.size());
    for (std::size_t m = 0; m < mesh.materials.size(); ++m)
        per_material[m].name = mesh.materials[m].name;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto p = std::size_t(y) * image.width + x;
            const Vec3 direction =
                view_ray(view, (x + 0.5) / image.width, (y + 0.5) / image.height);
            const auto hit = scene.trace(view.position, direction);
            if (hit.patch < 0) continue;
            auto& s = per_material[mesh.patches[std::size_t(hit.patch)].material];
            const double luminance = pixel_luminance(image, p);
            ++s.pixels;
            s.mean += luminance;
            s.max = std::max(s.max, luminance);
        }
    std::vector<SurfaceLuminance> seen;
    for (auto& s : per_material)
        if (s.pixels > 0) {
            s.mean /= double(s.pixels);
            seen.push_back(std::move(s));
        }
    return seen;
}

} // namespace rad
