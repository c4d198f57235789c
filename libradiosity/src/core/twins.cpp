// Twins: the patch on the same spot facing the other way (a two-sided surface's back, a thin
// sheet's other face), found by sorting the patches' corner positions.
#include "radiosity/twins.hpp"

#include "core/equal_keys.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>

namespace rad {

namespace {
// The corner positions of a patch, sorted: the same for a patch and its reverse.
std::vector<radfmt::Vec3> corner_key(const radfmt::MeshData& mesh, const radfmt::Patch& p) {
    std::vector<radfmt::Vec3> key;
    for (const auto v : mesh.corners(p)) key.push_back(mesh.vertices[v]);
    std::sort(key.begin(), key.end());
    return key;
}

} // namespace

std::vector<std::int64_t> find_twins(const radfmt::MeshData& mesh) {
    const std::size_t n = mesh.patches.size();
    const auto first =
        first_with_equal_key(n, [&](std::size_t i) { return corner_key(mesh, mesh.patches[i]); });
    std::vector<std::uint32_t> on_spot(n, 0); // patches on each spot, by its first patch
    for (std::size_t i = 0; i < n; ++i) ++on_spot[first[i]];
    std::vector<std::int64_t> twin(n, -1);
    for (std::size_t j = 0; j < n; ++j) {
        const auto i = first[j];
        // More than two on one spot: no pairing to trust.
        if (i == j || on_spot[i] != 2) continue;
        if (dot(mesh.patches[i].normal, mesh.patches[j].normal) < 0)
            twin[i] = static_cast<std::int64_t>(j), twin[j] = static_cast<std::int64_t>(i);
    }
    return twin;
}

} // namespace rad
