// Patch numbering in a locality order: a row of the form-factor matrix lists the patches a
// patch sees, and a solver gathers their radiosity by number; patches near each other in
// space should be near each other in memory.
#include "radiosity/scene.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rad {

namespace {
// The bits of a 21-bit number spread to every third bit.
std::uint64_t spread_bits(std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}
} // namespace

std::uint64_t morton_code(const Vec3& point, const Vec3& origin, double cell) {
    std::uint64_t code = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const double steps = std::floor((point[axis] - origin[axis]) / cell);
        const auto q = static_cast<std::uint64_t>(std::clamp(steps, 0.0, double(kMortonSteps - 1)));
        code |= spread_bits(q) << axis;
    }
    return code;
}

void order_patches_by_locality(radfmt::MeshData& mesh) {
    const std::size_t n = mesh.patches.size();
    if (n == 0) return;
    // The bounding cube of the centroids, cut into 2^21 steps a side (a cube, so the curve
    // treats every axis alike).
    Box box;
    for (const auto& p : mesh.patches) box.add(p.centroid);
    double side = 0;
    for (int axis = 0; axis < 3; ++axis) side = std::max(side, box.hi[axis] - box.lo[axis]);
    const double cell = side > 0 ? side / double(kMortonSteps) : 1.0;
    std::vector<std::uint64_t> code(n);
    for (std::size_t i = 0; i < n; ++i)
        code[i] = morton_code(mesh.patches[i].centroid, box.lo, cell);
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    // Stable: patches in one cell (a two-sided wall's front and back) keep their order.
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return code[a] < code[b]; });

    std::vector<radfmt::Patch> patches;
    patches.reserve(n);
    for (const auto i : order) patches.push_back(mesh.patches[i]);
    // Vertices renumbered in their first use by the new order (the unused ones last).
    std::vector<std::uint32_t> new_index(mesh.vertices.size(), radfmt::kNoVertex);
    std::vector<radfmt::Vec3> vertices;
    vertices.reserve(mesh.vertices.size());
    mesh.patches = std::move(patches);
    for (auto& p : mesh.patches)
        for (auto& corner : mesh.corners(p)) {
            if (new_index[corner] == radfmt::kNoVertex) {
                new_index[corner] = static_cast<std::uint32_t>(vertices.size());
                vertices.push_back(mesh.vertices[corner]);
            }
            corner = new_index[corner];
        }
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (new_index[v] == radfmt::kNoVertex) vertices.push_back(mesh.vertices[v]);
    mesh.vertices = std::move(vertices);
}

} // namespace rad
