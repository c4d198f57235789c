// Two-sided surfaces: a back patch for each selected patch (two_sided.hpp).
#include "radiosity/two_sided.hpp"

#include "radiosity/error.hpp"
#include "radiosity/twins.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <map>

namespace rad {

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
