// From per-patch radiosity to pictures: smoothing to vertices, a z-buffer rasteriser with
// perspective-correct interpolation, and OpenEXR / PNG / PLY output (rad-shade).
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <map>
#include <string>
#include <vector>

namespace rad {

// Radiance's view convention: -vp eye, -vd direction, -vu up, -vh/-vv full angles (deg).
struct View {
    Vec3 position{0, 0, 0};
    Vec3 direction{0, 0, 1};
    Vec3 up{0, 1, 0};
    double horizontal_deg = 45;
    double vertical_deg = 45;
};
// Parses "-vp x y z -vd x y z ..." (a leading "rvu" and -vtv are accepted); `source` names
// the text's origin in messages. Throws InputError for malformed or degenerate views.
View parse_view(const std::string& text, const std::string& source, View start = {});
View read_view_file(const std::string& path);

enum class Smoothing { Flat, Average, Area, Crease };
Smoothing parse_smoothing(const std::string& name);

// Colour at each corner of each patch. Average: the plain mean of the patches around a
// vertex (the paper's); Area: weighted by area; Crease: area-weighted over neighbours of
// the same material whose normals are within `crease_deg`, so edges stay sharp.
std::vector<std::array<Rgb, 4>> corner_colours(const radfmt::MeshData& mesh,
                                               const std::vector<Rgb>& patch, Smoothing mode,
                                               double crease_deg = 30);

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb; // row-major, top row first
    std::size_t covered_pixels = 0;
};

Image render(const radfmt::MeshData& mesh, const std::vector<std::array<Rgb, 4>>& corners,
             const View& view, int width, int height, int supersampling);

void write_exr(const std::string& path, const Image& image,
               const std::map<std::string, std::string>& attributes);
Image read_exr(const std::string& path, std::map<std::string, std::string>* attributes = nullptr);
// Multiplier that maps the 95th-percentile luminance of covered pixels to 0.8.
double auto_exposure(const Image& image);
void write_png(const std::string& path, const Image& image, double exposure);
void write_ply(const std::string& path, const radfmt::MeshData& mesh,
               const std::vector<std::array<Rgb, 4>>& corners, double exposure);
std::uint8_t to_srgb8(double linear);

} // namespace rad
