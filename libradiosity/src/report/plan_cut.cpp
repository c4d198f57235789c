// The room cut at a horizontal calculation surface's plane, for its plan: where walls,
// partitions, cabinets and the like cross the plane, as a designer's plan draws them.
#include "radiosity/report.hpp"

#include <algorithm>
#include <cmath>

namespace rad {
namespace {

// Keeps the part of segment a-b inside [u0, u1] x [v0, v1] (Liang-Barsky); false when none.
bool clip_to_rectangle(PlanSegment& s, double u0, double u1, double v0, double v1) {
    const double du = s.u1 - s.u0, dv = s.v1 - s.v0;
    double enter = 0, leave = 1;
    const double p[4] = {-du, du, -dv, dv};
    const double q[4] = {s.u0 - u0, u1 - s.u0, s.v0 - v0, v1 - s.v0};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0) {
            if (q[k] < 0) return false;
            continue;
        }
        const double t = q[k] / p[k];
        if (p[k] < 0)
            enter = std::max(enter, t);
        else
            leave = std::min(leave, t);
    }
    if (enter >= leave) return false;
    s = {s.u0 + enter * du, s.v0 + enter * dv, s.u0 + leave * du, s.v0 + leave * dv, s.glass};
    return true;
}

} // namespace

std::vector<PlanSegment> plan_cut(const radfmt::MeshData& mesh, const SurfaceGrid& grid,
                                  double metres_per_unit) {
    std::vector<PlanSegment> out;
    if (!horizontal_plan(grid) || grid.columns <= 0 || grid.rows <= 0) return out;
    const Vec3 u = normalized(grid.column_step), v = normalized(grid.row_step);
    // A centimetre in front of the surface: a floor's own plane would cut the walls along
    // their lower edges, where the floor meets them.
    const double lift = 0.01 / metres_per_unit;
    const Vec3 on_plane = grid.origin + grid.normal * lift;
    const auto height = [&](std::uint32_t vertex) {
        return dot(mesh.vertices[vertex] - on_plane, grid.normal);
    };
    const auto plan_of = [&](const Vec3& p) {
        return std::array<double, 2>{dot(p - grid.origin, u) * metres_per_unit,
                                     dot(p - grid.origin, v) * metres_per_unit};
    };
    // The surface with its border, and a millimetre: walls standing on its edges stay in.
    const double border = grid.border_m + 0.001;
    std::vector<std::array<double, 2>> crossings;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto corners = mesh.corners(i);
        crossings.clear();
        for (std::size_t k = 0; k < corners.size(); ++k) {
            const auto a = corners[k], b = corners[(k + 1) % corners.size()];
            const double ha = height(a), hb = height(b);
            if ((ha < 0) == (hb < 0)) continue;
            const double t = ha / (ha - hb);
            crossings.push_back(
                plan_of(mesh.vertices[a] + (mesh.vertices[b] - mesh.vertices[a]) * t));
        }
        if (crossings.size() < 2) continue;
        // A simple polygon crosses a line an even number of times; sorted along the line, the
        // crossings pair off into the pieces inside it.
        const double du = crossings.back()[0] - crossings.front()[0];
        const double dv = crossings.back()[1] - crossings.front()[1];
        std::sort(crossings.begin(), crossings.end(), [&](const auto& p, const auto& q) {
            return p[0] * du + p[1] * dv < q[0] * du + q[1] * dv;
        });
        for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
            const bool glass = mesh.materials[mesh.patches[i].material].specular.transmits();
            PlanSegment s{crossings[k][0], crossings[k][1], crossings[k + 1][0],
                          crossings[k + 1][1], glass};
            if (clip_to_rectangle(s, -border, grid.width_m + border, -border,
                                  grid.depth_m + border))
                out.push_back(s);
        }
    }
    return out;
}

} // namespace rad
