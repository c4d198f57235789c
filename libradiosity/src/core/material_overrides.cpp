// Materials as the options and messages name them: MATERIAL=r,g,b overrides read, colours
// written as the chain records them, the hint that names the rad-solve option fixing a
// material, the reflectances that would not converge (material_overrides.hpp).
#include "radiosity/material_overrides.hpp"

#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace rad {

MaterialOverride parse_material_override(const std::string& spec, const std::string& option) {
    const auto eq = spec.find('=');
    MaterialOverride o{};
    if (eq == std::string::npos || eq == 0)
        throw InputError(option + ": '" + spec + "' is not MATERIAL=r,g,b");
    o.material = spec.substr(0, eq);
    std::stringstream parts(spec.substr(eq + 1));
    std::string item;
    int count = 0;
    while (std::getline(parts, item, ',')) {
        if (count == 3) throw InputError(option + ": '" + spec + "' has more than 3 values");
        if (!parse_number(item, o.value[count]))
            throw InputError(option + ": '" + item + "' in '" + spec +
                             "' is not a number (finite, decimal)");
        if (o.value[count] < 0)
            throw InputError(option + ": values must be finite and non-negative in '" + spec + "'");
        ++count;
    }
    if (count == 1)
        o.value = {o.value[0], o.value[0], o.value[0]};
    else if (count != 3)
        throw InputError(option + ": '" + spec + "' needs 1 or 3 values");
    return o;
}

std::string rgb_text(const radfmt::Rgb& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", v[0], v[1], v[2]);
    return text;
}

std::string material_names(const radfmt::MeshData& mesh) {
    std::string list;
    for (const auto& m : mesh.materials) list += (list.empty() ? "" : ", ") + m.name;
    return list;
}

std::string material_hint(const std::string& material, const std::string& what,
                          const std::string& lead, const std::string& option,
                          const radfmt::Rgb& value) {
    std::string line = "material '";
    line += material;
    line += "' ";
    line += what;
    line += " (";
    if (!lead.empty()) {
        line += lead;
        line += ' ';
    }
    line += "rad-solve --";
    line += option;
    line += ' ';
    line += material;
    line += '=';
    line += rgb_text(value);
    line += ')';
    return line;
}

std::vector<std::string> reflectance_problems(const radfmt::MeshData& mesh) {
    std::vector<bool> used(mesh.materials.size(), false);
    for (const auto& p : mesh.patches) used[p.material] = true;
    std::vector<std::string> lines;
    for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
        const auto& mat = mesh.materials[m];
        if (!used[m]) continue;
        if (mat.reflectance[0] < 1 && mat.reflectance[1] < 1 && mat.reflectance[2] < 1) continue;
        radfmt::Rgb fixed = mat.reflectance;
        for (auto& v : fixed) v = std::min(v, 0.95);
        lines.push_back(material_hint(mat.name, "has reflectance " + rgb_text(mat.reflectance),
                                      "fix:", "reflectance", fixed));
    }
    return lines;
}

bool any_emitter(const radfmt::MeshData& mesh) {
    for (const auto& p : mesh.patches)
        if (mesh.materials[p.material].emits()) return true;
    return false;
}

} // namespace rad
