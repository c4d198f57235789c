// From one radiosity per patch to a colour per patch corner (vertex smoothing).
#include "radiosity/smoothing.hpp"

#include "radiosity/error.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

namespace rad {

namespace {
constexpr double kDeg = std::numbers::pi / 180;

// Whether point x, on patch r's plane, lies in r (convex, its corners counter-clockwise about
// its normal), its edges included.
bool inside_patch(const radfmt::MeshData& mesh, const radfmt::Patch& r, const Vec3& x) {
    const auto corners = mesh.corners(r);
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const Vec3 a = mesh.vertices[corners[k]],
                   b = mesh.vertices[corners[(k + 1) % corners.size()]];
        if (dot(cross(b - a, x - a), r.normal) < -1e-6 * dot(b - a, b - a)) return false;
    }
    return true;
}

// Whether a surface standing at the corner (a patch there at more than 60 degrees to p)
// separates patches p and q: the segment between their centroids goes through it. A wall
// between two rooms keeps the ceiling's light on each side from being averaged across it;
// around a block's corner the segment passes outside the block, and the floor is smoothed.
bool walled_apart(const radfmt::MeshData& mesh, std::span<const std::uint32_t> around,
                  const radfmt::Patch& p, const radfmt::Patch& q) {
    for (const auto w : around) {
        const auto& r = mesh.patches[w];
        if (std::abs(dot(r.normal, p.normal)) > 0.5) continue;
        const double sp = dot(p.centroid - r.centroid, r.normal);
        const double sq = dot(q.centroid - r.centroid, r.normal);
        if (!(sp * sq < 0)) continue;
        const Vec3 x = p.centroid + (q.centroid - p.centroid) * (sp / (sp - sq));
        if (inside_patch(mesh, r, x)) return true;
    }
    return false;
}

// After patch i's corners were set through CornerColours::at: its four-entry copy, which
// holds a polygon's first corners and repeats a triangle's corner 2 as corner 3.
void fill_four(const radfmt::MeshData& mesh, CornerColours& c, std::size_t i) {
    if (mesh.patches[i].is_polygon())
        for (std::size_t k = 0; k < 4; ++k) c[i][k] = c.at(mesh, i, k);
    else if (mesh.patches[i].corner_count() == 3)
        c[i][3] = c[i][2];
}
} // namespace

Smoothing parse_smoothing(const std::string& name) {
    if (name == "flat") return Smoothing::Flat;
    if (name == "average") return Smoothing::Average;
    if (name == "area") return Smoothing::Area;
    if (name == "crease") return Smoothing::Crease;
    throw InputError("unknown smoothing '" + name + "' (use average, area, crease or flat)");
}

CornerColours corner_colours(const radfmt::MeshData& mesh, const std::vector<Rgb>& patch,
                             Smoothing mode, double crease_deg) {
    const std::size_t n = mesh.patches.size();
    CornerColours out;
    out.patches.resize(n);
    out.polygon_corners.resize(mesh.polygon_corners.size());
    if (mode == Smoothing::Flat) {
        for (std::size_t i = 0; i < n; ++i) {
            out[i].fill(patch[i]);
            for (std::size_t k = 0; k < mesh.corners(i).size(); ++k) out.at(mesh, i, k) = patch[i];
        }
        return out;
    }
    std::vector<std::vector<std::uint32_t>> around(mesh.vertices.size());
    for (std::size_t i = 0; i < n; ++i)
        for (const auto v : mesh.corners(i)) around[v].push_back(static_cast<std::uint32_t>(i));
    const double cos_crease = std::cos(crease_deg * kDeg);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        const auto& p = mesh.patches[i];
        const auto corners = mesh.corners(i);
        for (std::size_t k = 0; k < corners.size(); ++k) {
            Rgb sum{0, 0, 0};
            double weight = 0;
            for (auto q : around[corners[k]]) {
                const auto& pq = mesh.patches[q];
                // A patch facing the opposite way at the same corner is the other side of a
                // sheet (a two-sided surface): its light is on the other side, never mixed.
                if (dot(pq.normal, p.normal) < -0.999) continue;
                if (mode == Smoothing::Crease &&
                    (pq.material != p.material || pq.group != p.group ||
                     dot(pq.normal, p.normal) < cos_crease))
                    continue;
                if (q != i && walled_apart(mesh, around[corners[k]], p, pq)) continue;
                const double w = mode == Smoothing::Average ? 1.0 : pq.area;
                for (int c = 0; c < 3; ++c) sum[c] += w * patch[q][c];
                weight += w;
            }
            auto& value = out.at(mesh, i, k);
            for (int c = 0; c < 3; ++c) value[c] = weight > 0 ? sum[c] / weight : patch[i][c];
        }
        fill_four(mesh, out, i);
    });
    return out;
}

namespace {
// The mean of a patch's corner values: over a polygon, its fan triangles' by area.
Rgb corner_mean(const radfmt::MeshData& mesh, const CornerColours& c, std::size_t patch) {
    const auto corners = mesh.corners(patch);
    Rgb mean{0, 0, 0};
    if (!mesh.patches[patch].is_polygon()) {
        for (std::size_t k = 0; k < corners.size(); ++k)
            for (int ch = 0; ch < 3; ++ch) mean[ch] += c.at(mesh, patch, k)[ch] / corners.size();
        return mean;
    }
    const Vec3 origin = mesh.vertices[corners[0]];
    double area = 0;
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        const double w = length(
            cross(mesh.vertices[corners[k]] - origin, mesh.vertices[corners[k + 1]] - origin));
        area += w;
        for (int ch = 0; ch < 3; ++ch)
            mean[ch] += w *
                        (c.at(mesh, patch, 0)[ch] + c.at(mesh, patch, k)[ch] +
                         c.at(mesh, patch, k + 1)[ch]) /
                        3;
    }
    for (int ch = 0; ch < 3; ++ch) mean[ch] = area > 0 ? mean[ch] / area : 0;
    return mean;
}
} // namespace

void keep_patch_means(const radfmt::MeshData& mesh, const std::vector<Rgb>& patch,
                      CornerColours& corners) {
    tbb::parallel_for(std::size_t(0), mesh.patches.size(), [&](std::size_t i) {
        const Rgb mean = corner_mean(mesh, corners, i);
        const std::size_t count = mesh.corners(i).size();
        for (std::size_t k = 0; k < count; ++k) {
            auto& value = corners.at(mesh, i, k);
            for (int ch = 0; ch < 3; ++ch)
                value[ch] = mean[ch] > 0 ? value[ch] * (patch[i][ch] / mean[ch]) : patch[i][ch];
        }
        fill_four(mesh, corners, i);
    });
}

Rgb interpolate_corners(const radfmt::MeshData& mesh, const CornerColours& c, std::int64_t hit,
                        double u, double v, std::int32_t piece_in) {
    const auto patch = static_cast<std::size_t>(hit);
    Rgb out;
    if (mesh.patches[patch].is_polygon()) {
        const auto piece = static_cast<std::size_t>(std::max(0, piece_in));
        const auto &c0 = c.at(mesh, patch, 0), &c1 = c.at(mesh, patch, piece + 1),
                   &c2 = c.at(mesh, patch, piece + 2);
        for (int k = 0; k < 3; ++k) out[k] = (1 - u - v) * c0[k] + u * c1[k] + v * c2[k];
        return out;
    }
    const auto& q = c[patch];
    const bool triangle = mesh.patches[patch].corner_count() == 3;
    for (int k = 0; k < 3; ++k)
        out[k] = triangle ? (1 - u - v) * q[0][k] + u * q[1][k] + v * q[2][k]
                          : (1 - u) * (1 - v) * q[0][k] + u * (1 - v) * q[1][k] + u * v * q[2][k] +
                                (1 - u) * v * q[3][k];
    return out;
}

} // namespace rad
