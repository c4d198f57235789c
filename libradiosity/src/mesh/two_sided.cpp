#include "radiosity/two_sided.hpp"

#include "core/equal_keys.hpp"
#include "radiosity/error.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <map>

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

radfmt::Patch back_of(radfmt::MeshData& mesh, const radfmt::Patch& front) {
    radfmt::Patch back = front;
    const auto corners = mesh.corners(front);
    std::vector<std::uint32_t> reversed(corners.rbegin(), corners.rend());
    if (front.is_polygon()) std::rotate(reversed.begin(), reversed.end() - 1, reversed.end());
    mesh.set_corners(back, reversed, front.is_polygon());
    back.normal = front.normal * -1.0;
    return back;
}

TwoSidedReport make_two_sided(radfmt::MeshData& mesh, const std::vector<std::string>& selection,
                              bool emission_on_both_sides) {
    std::vector<bool> group_selected(mesh.groups.size(), false);
    std::vector<bool> material_selected(mesh.materials.size(), false);
    for (const auto& name : selection) {
        bool found = false;
        for (std::size_t g = 0; g < mesh.groups.size(); ++g)
            if (name == "all" || mesh.groups[g] == name) group_selected[g] = found = true;
        for (std::size_t m = 0; m < mesh.materials.size(); ++m)
            if (name == "all" || mesh.materials[m].name == name)
                material_selected[m] = found = true;
        if (!found) {
            std::string known = "groups:";
            for (const auto& g : mesh.groups) known += " " + g;
            known += "; materials:";
            for (const auto& m : mesh.materials) known += " " + m.name;
            throw InputError("--two-sided: '" + name +
                             "' is neither a group nor a material of the scene (" + known +
                             "; or 'all')");
        }
    }
    TwoSidedReport report;
    const auto twins = find_twins(mesh);
    // Emitting materials get a non-emitting copy for their backs, made once.
    std::map<std::uint32_t, std::uint32_t> back_material;
    const std::size_t front_count = mesh.patches.size();
    for (std::size_t i = 0; i < front_count; ++i) {
        const auto front = mesh.patches[i];
        if (twins[i] >= 0 || !(group_selected[front.group] || material_selected[front.material]))
            continue;
        radfmt::Patch back = back_of(mesh, front);
        const auto& material = mesh.materials[front.material];
        if (material.emits() && !emission_on_both_sides) {
            auto [it, added] = back_material.try_emplace(
                front.material, static_cast<std::uint32_t>(mesh.materials.size()));
            if (added) {
                radfmt::Material copy = material;
                copy.name += ".back";
                copy.emission = {};
                report.unlit_back_materials.push_back(material.name);
                mesh.materials.push_back(std::move(copy));
            }
            back.material = it->second;
        }
        mesh.patches.push_back(back);
        ++report.back_patches;
    }
    return report;
}

} // namespace rad
