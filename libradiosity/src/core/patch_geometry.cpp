#include "radiosity/patch_geometry.hpp"

namespace rad {

std::vector<std::array<std::uint32_t, 3>> patch_triangles(const radfmt::MeshData& mesh,
                                                          std::size_t patch) {
    const auto n = static_cast<std::uint32_t>(mesh.patches[patch].corner_count());
    std::vector<std::array<std::uint32_t, 3>> fan;
    for (std::uint32_t k = 1; k + 1 < n; ++k) fan.push_back({0, k, k + 1});
    return fan;
}

std::vector<Vec3> patch_points(const radfmt::MeshData& mesh, std::size_t patch) {
    std::vector<Vec3> points;
    for (const auto v : mesh.corners(patch)) points.push_back(mesh.vertices[v]);
    return points;
}

std::span<const Vec3> patch_points(const radfmt::MeshData& mesh, std::size_t patch,
                                   std::array<Vec3, 4>& few, std::vector<Vec3>& many) {
    const auto corners = mesh.corners(patch);
    Vec3* out = few.data();
    if (corners.size() > few.size()) {
        many.resize(corners.size());
        out = many.data();
    }
    for (std::size_t k = 0; k < corners.size(); ++k) out[k] = mesh.vertices[corners[k]];
    return {out, corners.size()};
}

} // namespace rad
