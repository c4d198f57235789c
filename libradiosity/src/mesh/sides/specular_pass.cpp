// The specular pass: --thin made panes of the named materials or groups, and a note for each
// mirror and glass the mesh has, saying how the chain takes it.
#include "radiosity/build_mesh.hpp"
#include "radiosity/error.hpp"
#include "radiosity/material_overrides.hpp"
#include "radiosity/specular_materials.hpp"

#include <algorithm>
#include <map>

namespace rad {

namespace {
using radfmt::SpecularKind;

// The index of `name` among `names`, or -1.
long index_of(const std::vector<std::string>& names, const std::string& name) {
    const auto at = std::find(names.begin(), names.end(), name);
    return at == names.end() ? -1 : at - names.begin();
}

std::vector<std::string> names_of_materials(const radfmt::MeshData& mesh) {
    std::vector<std::string> names;
    for (const auto& m : mesh.materials) names.push_back(m.name);
    return names;
}

// A group's refracting materials are made panes in copies ("glass thin"), so the same
// material elsewhere keeps refracting.
std::size_t thin_group(radfmt::MeshData& mesh, std::uint32_t group) {
    std::map<std::uint32_t, std::uint32_t> copy_of;
    std::size_t patches = 0;
    for (auto& p : mesh.patches) {
        if (p.group != group) continue;
        const auto& material = mesh.materials[p.material];
        if (material.specular.kind != SpecularKind::dielectric) continue;
        auto [at, added] = copy_of.try_emplace(p.material, 0);
        if (added) {
            auto thin = material;
            thin.name += " thin";
            while (index_of(names_of_materials(mesh), thin.name) >= 0) thin.name += "_";
            thin.specular = as_thin_pane(thin.specular, thin.reflectance);
            at->second = static_cast<std::uint32_t>(mesh.materials.size());
            mesh.materials.push_back(std::move(thin));
        }
        p.material = at->second;
        ++patches;
    }
    return patches;
}

} // namespace

namespace {
// --transmittance MATERIAL=r,g,b: a pane's transmittance at normal incidence, or what a
// passage through a refracting solid keeps, instead of what the scene file says. 0 makes the
// material opaque; a value above 0 makes an opaque one a thin pane of glass (an exporter that
// wrote glass as opaque). Kd is lowered where the glass then leaves it less.
void set_transmittance(radfmt::MeshData& mesh, const std::string& spec, MeshReport& report) {
    const auto given = parse_material_override(spec, "--transmittance");
    const long m = index_of(names_of_materials(mesh), given.material);
    if (m < 0)
        throw InputError("--transmittance " + spec + ": no material '" + given.material +
                         "' (it has: " + rad::material_names(mesh) + ")");
    for (int k = 0; k < 3; ++k)
        if (given.value[k] > 1) throw InputError("--transmittance " + spec + ": a share above 1");
    auto& material = mesh.materials[static_cast<std::size_t>(m)];
    auto& specular = material.specular;
    const std::string what = "material '" + given.material + "': ";
    const auto was = specular_summary(specular);
    if (given.value == radfmt::Rgb{}) {
        if (specular.transmits()) specular = {};
        report.add(MeshReport::Kind::Change,
                   what + "opaque (--transmittance 0; its file: " + was + ")");
        return;
    }
    if (specular.mirrors())
        throw InputError("--transmittance " + spec + ": material '" + given.material +
                         "' is a mirror in its file (" + was +
                         "), and a mirror lets nothing through");
    if (specular.kind == SpecularKind::none) {
        specular.kind = SpecularKind::pane;
        specular.ior = kPaneIndex;
    }
    specular.transmittance = given.value;
    std::string text = what + "transmittance " + rgb_text(given.value) +
                       " (--transmittance; its file: " + was + ")";
    if (const auto fitted = fit_specular_energy(material); !fitted.empty()) text += "; " + fitted;
    report.add(MeshReport::Kind::Change, text);
}
} // namespace

void specular_pass(radfmt::MeshData& mesh, const MeshOptions& options, MeshReport& report) {
    for (const auto& spec : options.transmittance) set_transmittance(mesh, spec, report);
    for (const auto& name : options.thin) {
        const auto names = names_of_materials(mesh);
        if (const long m = index_of(names, name); m >= 0) {
            auto& material = mesh.materials[static_cast<std::size_t>(m)];
            if (material.specular.kind != SpecularKind::dielectric)
                throw InputError("--thin " + name + ": material '" + name + "' is a " +
                                 specular_summary(material.specular) +
                                 ", not a refracting one (illum 6 or 7, or a glTF volume)");
            material.specular = as_thin_pane(material.specular, material.reflectance);
            report.add(MeshReport::Kind::Change, "material '" + name + "' is a thin pane (--thin)");
            continue;
        }
        if (const long g = index_of(mesh.groups, name); g >= 0) {
            const auto patches = thin_group(mesh, static_cast<std::uint32_t>(g));
            if (patches == 0)
                throw InputError("--thin " + name + ": group '" + name +
                                 "' has no refracting material (illum 6 or 7, or a glTF volume)");
            report.add(MeshReport::Kind::Change,
                       "group '" + name + "': " + std::to_string(patches) +
                           " patch(es) of glass made thin panes (--thin)");
            continue;
        }
        std::string known;
        for (const auto& m : mesh.materials)
            if (m.specular.kind == SpecularKind::dielectric) known += " " + m.name;
        throw InputError("--thin " + name +
                         ": no material or group of that name (refracting "
                         "materials:" +
                         (known.empty() ? std::string(" none") : known) + ")");
    }
    for (const auto m : mesh.specular_materials()) {
        const auto what = "material '" + mesh.materials[m].name + "': ";
        // A line from the load pass (how its file was read) or --transmittance says it already.
        const bool said =
            std::any_of(report.lines.begin(), report.lines.end(),
                        [&](const auto& line) { return line.text.rfind(what, 0) == 0; });
        if (!said)
            report.add(MeshReport::Kind::Note, what + specular_summary(mesh.materials[m].specular));
    }
}

} // namespace rad
