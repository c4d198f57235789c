// Names made the chain's (radfmt/names.hpp): UTF-8 text without control characters, at most
// 200 bytes, so that every output (headers, glTF's JSON, EXR layers) takes them and reads back.
#include "radfmt/names.hpp"
#include "radiosity/build_mesh.hpp"

#include <set>

namespace rad {
namespace {
// Cleans `names` in place, each still unique (a clean name already taken gets "~2", "~3"...);
// returns "'old' -> 'new'" for the first changed one and counts the changes.
std::size_t clean_all(std::vector<std::string>& names, std::string& first) {
    std::set<std::string> taken(names.begin(), names.end());
    std::size_t changed = 0;
    for (auto& name : names) {
        if (radfmt::name_problem(name).empty()) continue;
        auto clean = radfmt::clean_name(name);
        const auto base = clean.substr(0, radfmt::kMaxNameBytes - 8);
        for (int k = 2; taken.count(clean); ++k) clean = base + "~" + std::to_string(k);
        taken.insert(clean);
        if (changed++ == 0)
            first = radfmt::shown_name(name) + "' is '" + radfmt::shown_name(clean) + "'";
        name = clean;
    }
    return changed;
}
} // namespace

void names_pass(radfmt::MeshData& mesh, MeshReport& report) {
    std::string first_group, first_material;
    const auto groups = clean_all(mesh.groups, first_group);
    std::vector<std::string> names;
    for (const auto& m : mesh.materials) names.push_back(m.name);
    const auto materials = clean_all(names, first_material);
    for (std::size_t k = 0; k < names.size(); ++k) mesh.materials[k].name = names[k];
    const auto say = [&](std::size_t count, const char* what, const std::string& first) {
        if (count == 0) return;
        report.add(MeshReport::Kind::Change,
                   "names: " + std::to_string(count) + " " + what +
                       " name(s) made UTF-8 text of at most 200 bytes without control "
                       "characters (bytes that were not UTF-8 read as Latin-1), first '" +
                       first);
    };
    say(groups, "group", first_group);
    say(materials, "material", first_material);
}

} // namespace rad
