#include "radiosity/light_groups.hpp"

#include "radfmt/names.hpp"
#include "radiosity/error.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/text_input.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace rad {

std::vector<LightGroup> light_groups(const radfmt::MeshData& mesh,
                                     const std::vector<std::string>& specs) {
    std::vector<LightGroup> groups;
    std::map<std::uint32_t, std::string> taken; // material -> its group
    std::vector<bool> used(mesh.materials.size(), false);
    for (const auto& p : mesh.patches) used[p.material] = true;
    for (const auto& spec : specs) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
            throw InputError("--group: '" + spec + "' is not NAME=MATERIAL[,MATERIAL...]");
        LightGroup group{spec.substr(0, eq), {}};
        if (const auto why = radfmt::name_problem(group.name); !why.empty())
            throw InputError("--group: " + quoted_prefix(group.name) + " is " + why +
                             ": a light group's name is UTF-8 text of at most " +
                             std::to_string(radfmt::kMaxNameBytes) +
                             " bytes without control characters");
        for (const auto& g : groups)
            if (g.name == group.name)
                throw InputError("--group: group '" + group.name + "' is defined twice");
        std::stringstream list(spec.substr(eq + 1));
        for (std::string name; std::getline(list, name, ',');) {
            const auto it = std::find_if(mesh.materials.begin(), mesh.materials.end(),
                                         [&](const auto& m) { return m.name == name; });
            if (it == mesh.materials.end())
                throw InputError("--group " + group.name + ": no material '" + name +
                                 "' (the mesh has: " + material_names(mesh) + ")");
            const auto index = static_cast<std::uint32_t>(it - mesh.materials.begin());
            if (const auto t = taken.find(index); t != taken.end())
                throw InputError("--group " + group.name + ": material '" + name +
                                 "' is already in group '" + t->second + "'");
            taken[index] = group.name;
            group.materials.push_back(index);
        }
        if (std::none_of(group.materials.begin(), group.materials.end(),
                         [&](auto m) { return mesh.materials[m].emits(); }))
            throw InputError("--group " + group.name +
                             ": none of its materials emits (give one Ke, or --emission)");
        groups.push_back(std::move(group));
    }
    for (std::uint32_t m = 0; m < mesh.materials.size(); ++m) {
        if (!used[m] || !mesh.materials[m].emits() || taken.count(m)) continue;
        const auto& name = mesh.materials[m].name;
        for (const auto& g : groups)
            if (g.name == name)
                throw InputError("light group '" + name +
                                 "' is both a --group and an emitting material outside it "
                                 "(name the group differently)");
        groups.push_back({name, {m}});
    }
    if (groups.empty())
        throw InputError("--light-groups: no material emits light (Ke > 0), so there is "
                         "nothing to group");
    return groups;
}

Channels grouped_emission(const radfmt::MeshData& mesh, const std::vector<LightGroup>& groups) {
    Channels e(mesh.patches.size(), 3 * groups.size());
    std::vector<int> group_of(mesh.materials.size(), -1);
    for (std::size_t g = 0; g < groups.size(); ++g)
        for (auto m : groups[g].materials) group_of[m] = static_cast<int>(g);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto material = mesh.patches[i].material;
        if (group_of[material] < 0) continue;
        for (int c = 0; c < 3; ++c)
            e.at(i, 3 * group_of[material] + c) = mesh.materials[material].emission[c];
    }
    return e;
}

void record_light_groups(radfmt::Header& header, const radfmt::MeshData& mesh,
                         const std::vector<LightGroup>& groups) {
    for (const auto& g : groups) {
        std::string value;
        for (auto m : g.materials) {
            if (!value.empty()) value += ' ';
            value += mesh.materials[m].name;
            value += '=';
            value += rgb_text(mesh.materials[m].emission);
        }
        header.set("light_group." + g.name, value);
    }
}

radfmt::RadiosityData radiosity_data(const Channels& solution,
                                     const std::vector<LightGroup>& groups) {
    radfmt::RadiosityData rad;
    const std::size_t n = solution.patches();
    rad.radiosity.assign(n, radfmt::Rgb{});
    if (groups.empty()) {
        rad.radiosity = to_rgb(solution);
        return rad;
    }
    for (const auto& g : groups) rad.group_names.push_back(g.name);
    rad.group_radiosity.resize(n * groups.size());
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t g = 0; g < groups.size(); ++g)
            for (int c = 0; c < 3; ++c) {
                const double b = solution.at(i, 3 * g + c);
                rad.group_radiosity[i * groups.size() + g][c] = b;
                rad.radiosity[i][c] += b;
            }
    return rad;
}

std::vector<radfmt::Rgb> mix_weights(const radfmt::RadiosityData& rad,
                                     const std::vector<std::string>& mix, bool mix_only,
                                     const std::string& path) {
    if (rad.group_count() == 0)
        throw InputError(path + " has no light groups to mix (solve with rad-solve "
                                "--light-groups)");
    std::vector<radfmt::Rgb> weight(rad.group_count(),
                                    mix_only ? radfmt::Rgb{} : radfmt::Rgb{{1, 1, 1}});
    for (const auto& spec : mix) {
        const auto w = parse_material_override(spec, "--mix");
        const auto it = std::find(rad.group_names.begin(), rad.group_names.end(), w.material);
        if (it == rad.group_names.end()) {
            std::string known;
            for (const auto& g : rad.group_names) known += (known.empty() ? "" : ", ") + g;
            throw InputError("--mix: no light group '" + w.material + "' in " + path +
                             " (it has: " + known + ")");
        }
        weight[static_cast<std::size_t>(it - rad.group_names.begin())] = w.value;
    }
    return weight;
}

std::vector<radfmt::Rgb> mix_light_groups(const radfmt::RadiosityData& rad,
                                          const std::vector<std::string>& mix, bool mix_only,
                                          const std::string& path) {
    if (mix.empty() && !mix_only) return rad.radiosity;
    const auto weight = mix_weights(rad, mix, mix_only, path);
    std::vector<radfmt::Rgb> out(rad.radiosity.size(), radfmt::Rgb{});
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t g = 0; g < rad.group_count(); ++g)
            for (int c = 0; c < 3; ++c) out[i][c] += weight[g][c] * rad.of_group(i, g)[c];
    return out;
}

} // namespace rad
