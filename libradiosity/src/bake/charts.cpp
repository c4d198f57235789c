// Charts for a lightmap: patches grown into flat pieces across shared edges, laid into a plane.
#include "radiosity/bake.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace rad {

namespace {

using EdgeMap = std::unordered_map<std::uint64_t, std::vector<std::uint32_t>>;

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
}

// The patches on each edge (by its two vertex indices).
EdgeMap patches_by_edge(const radfmt::MeshData& mesh) {
    EdgeMap edges;
    for (std::uint32_t i = 0; i < mesh.patches.size(); ++i) {
        const auto corners = mesh.corners(i);
        const auto n = corners.size();
        for (std::size_t k = 0; k < n; ++k)
            edges[edge_key(corners[k], corners[(k + 1) % n])].push_back(i);
    }
    return edges;
}

// Grows one chart from `seed` breadth first: same material and group, normal within the angle
// of the seed's. Patches are taken in the order they are reached, so the chart is deterministic.
std::vector<std::uint32_t> grow_chart(const radfmt::MeshData& mesh, const EdgeMap& edges,
                                      std::uint32_t seed, double min_cos,
                                      std::vector<bool>& taken) {
    const auto& first = mesh.patches[seed];
    std::vector<std::uint32_t> chart{seed};
    taken[seed] = true;
    for (std::size_t next = 0; next < chart.size(); ++next) {
        const auto corners = mesh.corners(chart[next]);
        const auto n = corners.size();
        for (std::size_t k = 0; k < n; ++k) {
            for (const auto j : edges.at(edge_key(corners[k], corners[(k + 1) % n]))) {
                const auto& q = mesh.patches[j];
                if (taken[j] || q.material != first.material || q.group != first.group ||
                    dot(q.normal, first.normal) < min_cos)
                    continue;
                taken[j] = true;
                chart.push_back(j);
            }
        }
    }
    return chart;
}

// Lays the chart's corners into the seed patch's plane, axes along its first edge.
Chart flatten_chart(const radfmt::MeshData& mesh, std::vector<std::uint32_t> patches) {
    const auto& seed = mesh.patches[patches.front()];
    const auto seed_corners = mesh.corners(patches.front());
    const Vec3 origin = mesh.vertices[seed_corners[0]];
    const Vec3 edge = mesh.vertices[seed_corners[1]] - origin;
    const Vec3 u = normalized(edge - seed.normal * dot(edge, seed.normal));
    const Vec3 v = cross(seed.normal, u);
    Chart chart;
    chart.corner_uv.resize(patches.size());
    double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    double hi[2] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
    for (std::size_t i = 0; i < patches.size(); ++i) {
        for (const auto corner : mesh.corners(patches[i])) {
            const Vec3 d = mesh.vertices[corner] - origin;
            const std::array<double, 2> uv{dot(d, u), dot(d, v)};
            chart.corner_uv[i].push_back(uv);
            for (int a = 0; a < 2; ++a)
                lo[a] = std::min(lo[a], uv[a]), hi[a] = std::max(hi[a], uv[a]);
        }
    }
    for (auto& patch : chart.corner_uv)
        for (auto& uv : patch)
            for (int a = 0; a < 2; ++a) uv[a] -= lo[a];
    chart.width = hi[0] - lo[0];
    chart.height = hi[1] - lo[1];
    chart.patches = std::move(patches);
    return chart;
}

} // namespace

std::vector<Chart> build_charts(const radfmt::MeshData& mesh, double max_angle_deg) {
    const double min_cos = std::cos(max_angle_deg * std::numbers::pi / 180);
    const EdgeMap edges = patches_by_edge(mesh);
    std::vector<bool> taken(mesh.patches.size(), false);
    std::vector<Chart> charts;
    for (std::uint32_t i = 0; i < mesh.patches.size(); ++i)
        if (!taken[i])
            charts.push_back(flatten_chart(mesh, grow_chart(mesh, edges, i, min_cos, taken)));
    return charts;
}

} // namespace rad
