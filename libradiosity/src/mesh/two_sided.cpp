#include "radiosity/two_sided.hpp"

#include "radiosity/error.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <bit>
#include <map>

namespace rad {

namespace {
// The corner positions of a patch, sorted: the same for a patch and its reverse.
std::vector<radfmt::Vec3> corner_key(const radfmt::MeshData& mesh, const radfmt::Patch& p) {
    std::vector<radfmt::Vec3> key;
    for (int k = 0; k < p.corner_count(); ++k) key.push_back(mesh.vertices[p.corners[k]]);
    std::sort(key.begin(), key.end());
    return key;
}

std::uint64_t mix(std::uint64_t h, double x) {
    // splitmix64's finaliser over the running hash and the value (-0 counted as 0).
    h ^= std::bit_cast<std::uint64_t>(x + 0.0) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h ^= h >> 30, h *= 0xbf58476d1ce4e5b9ULL, h ^= h >> 27, h *= 0x94d049bb133111ebULL;
    return h ^ (h >> 31);
}
} // namespace

std::vector<std::int64_t> find_twins(const radfmt::MeshData& mesh) {
    // Patches by a hash of their sorted corners (a map keyed by the corners themselves costs
    // a node and two allocations a patch); equal hashes are compared corner by corner.
    const std::size_t n = mesh.patches.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> by_hash(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint64_t h = 0;
        for (const auto& corner : corner_key(mesh, mesh.patches[i]))
            for (const double x : corner) h = mix(h, x);
        by_hash[i] = {h, static_cast<std::uint32_t>(i)};
    }
    std::sort(by_hash.begin(), by_hash.end());
    std::vector<std::int64_t> twin(n, -1);
    for (std::size_t start = 0; start < n;) {
        std::size_t end = start + 1;
        while (end < n && by_hash[end].first == by_hash[start].first) ++end;
        // Within one hash, the patches on each spot (almost always one spot).
        std::vector<std::pair<std::vector<radfmt::Vec3>, std::uint32_t>> spots;
        if (end - start >= 2)
            for (auto k = start; k < end; ++k)
                spots.emplace_back(corner_key(mesh, mesh.patches[by_hash[k].second]),
                                   by_hash[k].second);
        std::sort(spots.begin(), spots.end());
        for (std::size_t a = 0; a < spots.size();) {
            std::size_t b = a + 1;
            while (b < spots.size() && spots[b].first == spots[a].first) ++b;
            // More than two on one spot: no pairing to trust.
            if (b - a == 2) {
                const auto i = spots[a].second, j = spots[a + 1].second;
                if (dot(mesh.patches[i].normal, mesh.patches[j].normal) < 0)
                    twin[i] = j, twin[j] = i;
            }
            a = b;
        }
        start = end;
    }
    return twin;
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
        radfmt::Patch back = front;
        const int n = front.corner_count();
        for (int k = 0; k < n; ++k) back.corners[k] = front.corners[n - 1 - k];
        back.normal = front.normal * -1.0;
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
