// Vertex smoothing: from one radiosity per patch to a colour per patch corner.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <string>
#include <vector>

namespace rad {

enum class Smoothing { Flat, Average, Area, Crease };
Smoothing parse_smoothing(const std::string& name);

// A colour at each corner of each patch: four a patch for triangles and quads (a triangle's
// corner 3 repeats its corner 2), and a polygon's one per entry of mesh.polygon_corners.
struct CornerColours {
    std::vector<std::array<Rgb, 4>> patches; // a polygon's entry holds its first corners
    std::vector<Rgb> polygon_corners;
    CornerColours() = default;
    CornerColours(std::vector<std::array<Rgb, 4>> four) : patches(std::move(four)) {}
    std::size_t size() const { return patches.size(); }
    // The four of a triangle or quad.
    std::array<Rgb, 4>& operator[](std::size_t patch) { return patches[patch]; }
    const std::array<Rgb, 4>& operator[](std::size_t patch) const { return patches[patch]; }
    // Corner k of any patch.
    const Rgb& at(const radfmt::MeshData& mesh, std::size_t patch, std::size_t k) const {
        const auto& p = mesh.patches[patch];
        return p.is_polygon() ? polygon_corners[p.corners[0] + k] : patches[patch][k];
    }
    Rgb& at(const radfmt::MeshData& mesh, std::size_t patch, std::size_t k) {
        const auto& p = mesh.patches[patch];
        return p.is_polygon() ? polygon_corners[p.corners[0] + k] : patches[patch][k];
    }
};

// Colour at each corner of each patch. Average: the plain mean of the patches around a
// vertex (the paper's); Area: weighted by area; Crease: area-weighted over neighbours of
// the same material whose normals are within `crease_deg`, so edges stay sharp.
CornerColours corner_colours(const radfmt::MeshData& mesh, const std::vector<Rgb>& patch,
                             Smoothing mode, double crease_deg = 30);

// `corners` scaled patch by patch so that the mean of each patch's corner values (the
// interpolant's mean over a triangle or a parallelogram; a polygon's, its fan triangles' by
// area) is its value in `patch` again, the slope inside kept: averaging at corners lifts a
// dark patch among brighter ones (a floor in a narrow gap, read from a point beside it, came
// out 2% bright). Not continuous across edges: for light gathered by rays, which blur it,
// not for pictures of the surfaces themselves.
void keep_patch_means(const radfmt::MeshData& mesh, const std::vector<Rgb>& patch,
                      CornerColours& corners);

// The corner values where a ray met a patch: bilinear on a quad, barycentric on a triangle
// or on the polygon's fan triangle the ray met (RayScene::Hit's u, v and piece).
Rgb interpolate_corners(const radfmt::MeshData& mesh, const CornerColours& corners,
                        std::int64_t patch, double u, double v, std::int32_t piece);

} // namespace rad
