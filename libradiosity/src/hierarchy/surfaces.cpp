#include "hierarchy/surfaces.hpp"

#include "radiosity/vec.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

namespace rad::hierarchy {

namespace {
// Per patch, the index of its plane and material (in order of first patch).
std::vector<std::uint32_t> planes_of(const radfmt::MeshData& mesh) {
    const double size = std::max(bounds(mesh.vertices).diagonal(), 1e-300);
    auto q = [](double v, double step) { return static_cast<long long>(std::llround(v / step)); };
    std::map<std::tuple<std::uint32_t, long long, long long, long long, long long>, std::uint32_t>
        index;
    std::vector<std::uint32_t> plane(mesh.patches.size());
    for (std::uint32_t p = 0; p < mesh.patches.size(); ++p) {
        const auto& patch = mesh.patches[p];
        const auto key = std::make_tuple(patch.material, q(patch.normal[0], 1e-6),
                                         q(patch.normal[1], 1e-6), q(patch.normal[2], 1e-6),
                                         q(dot(patch.normal, patch.centroid), 1e-6 * size));
        plane[p] = index.emplace(key, static_cast<std::uint32_t>(index.size())).first->second;
    }
    return plane;
}

std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}
} // namespace

std::vector<std::uint32_t> connected_surfaces(const radfmt::MeshData& mesh) {
    const auto plane = planes_of(mesh);
    // Union-find over patches: patches of one plane that share a corner are joined.
    std::vector<std::uint32_t> parent(mesh.patches.size());
    std::iota(parent.begin(), parent.end(), 0u);
    // (vertex, plane, patch) per corner: sorted, a plane's patches at one vertex are adjacent.
    std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> corners;
    for (std::uint32_t p = 0; p < mesh.patches.size(); ++p)
        for (const auto v : mesh.corners(p)) corners.emplace_back(v, plane[p], p);
    std::sort(corners.begin(), corners.end());
    for (std::size_t k = 1; k < corners.size(); ++k) {
        const auto& [vertex, on, p] = corners[k];
        const auto& [vertex0, on0, p0] = corners[k - 1];
        if (vertex != vertex0 || on != on0) continue;
        const auto a = find(parent, p), b = find(parent, p0);
        parent[std::max(a, b)] = std::min(a, b); // the root is the set's first patch
    }
    // Number the surfaces by their first patch.
    std::vector<std::uint32_t> surface(mesh.patches.size());
    std::vector<std::uint32_t> number(mesh.patches.size(), UINT32_MAX);
    std::uint32_t count = 0;
    for (std::uint32_t p = 0; p < mesh.patches.size(); ++p) {
        const auto root = find(parent, p);
        if (number[root] == UINT32_MAX) number[root] = count++;
        surface[p] = number[root];
    }
    return surface;
}

} // namespace rad::hierarchy
