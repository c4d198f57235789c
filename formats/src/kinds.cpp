// The chain files' kinds: what every kind shares (light-group names and rows, the counts a
// header states) and the kind table rad-info reads each kind's CSV and summary from. Each kind
// has a file of its own (mesh.cpp, formfactors.cpp, radiosity.cpp, links.cpp,
// luminaires.cpp, daylight.cpp).
#include "radfmt/kinds.hpp"
#include "radfmt/names.hpp"

#include "body_checks.hpp"
#include "kind_table.hpp"

#include <cstdio>
#include <ostream>

namespace radfmt {
namespace fs = std::filesystem;

std::vector<std::string> detail::read_group_names(BodyReader& r, std::uint64_t count) {
    std::vector<std::string> names;
    for (std::uint64_t g = 0; g < count; ++g) {
        names.push_back(r.string());
        if (const auto why = name_problem(names.back()); !why.empty())
            r.fail("light group " + std::to_string(g) + " has " + why);
    }
    return names;
}

void detail::write_group_rows(std::ostream& out, const std::vector<std::string>& groups,
                              std::span<const Rgb> values) {
    char line[160];
    const std::size_t n = groups.empty() ? 0 : values.size() / groups.size();
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t g = 0; g < groups.size(); ++g) {
            const auto& v = values[i * groups.size() + g];
            std::snprintf(line, sizeof line, "%zu,", i);
            out << line << groups[g];
            std::snprintf(line, sizeof line, ",%.10g,%.10g,%.10g\n", v[0], v[1], v[2]);
            out << line;
        }
        if (!out) return;
    }
}

void detail::require_count(const Header& header, const char* key, std::uint64_t count,
                           BodyReader& r) {
    const auto* value = header.find(key);
    if (value && *value != std::to_string(count))
        r.fail(std::string("the header says ") + key + "=" + *value + " but the body holds " +
               std::to_string(count));
}

namespace {
constexpr KindInfo kKinds[] = {
    {Kind::Mesh, "mesh", "patch mesh", 3, 1,
     "patch,group,material,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,e_r,e_g,e_b,corners",
     detail::mesh_csv, detail::mesh_summary},
    {Kind::FormFactors, "formfactors", "form-factor matrix", 3, 1, "row,col,f",
     detail::form_factor_csv, detail::form_factor_summary},
    {Kind::FormFactorPart, "formfactor-part", "form-factor rows (a shard of rad-ff --rows)", 1, 1,
     "row,col,f", detail::form_factor_part_csv, detail::form_factor_part_summary},
    {Kind::Radiosity, "radiosity", "radiosity solution", 2, 1,
     "patch,b_r,b_g,b_b (with light groups: patch,group,b_r,b_g,b_b)", detail::radiosity_csv,
     detail::radiosity_summary},
    {Kind::Links, "links", "link hierarchy (hierarchical form factors)", 2, 2,
     "node,first,count,source,f,r0,r1,r2,r3,s0,s1,s2,s3 (shares in 65535ths)", detail::links_csv,
     detail::links_summary},
    {Kind::Luminaires, "luminaires", "luminaires' direct light per patch (rad-ff --luminaires)", 1,
     1, "patch,group,e_r,e_g,e_b (direct irradiance, W/m^2)", detail::luminaires_csv,
     detail::luminaires_summary},
    {Kind::Sky, "sky", "sky patches' light per patch at unit radiance (rad-ff --sky)", 1, 1,
     "patch,sky_patch,d_r,d_g,d_b (irradiance per unit radiance, sr)", detail::sky_csv,
     detail::sky_summary},
    {Kind::Annual, "annual", "a year of illuminance at sensors (rad-gather --annual)", 1, 1,
     "month,day,hour,occupied,then each sensor's lux", detail::annual_csv, detail::annual_summary},
};

} // namespace

std::span<const KindInfo> kind_table() {
    return kKinds;
}

const KindInfo& kind_info(Kind kind) {
    for (const auto& k : kKinds)
        if (k.kind == kind) return k;
    throw std::logic_error("file kind missing from the kind table");
}

std::string_view kind_name(Kind kind) {
    return kind_info(kind).name;
}
std::string_view kind_description(Kind kind) {
    return kind_info(kind).description;
}
std::uint32_t kind_version(Kind kind) {
    return kind_info(kind).version;
}
bool parse_kind(std::string_view name, Kind& kind) {
    for (const auto& k : kKinds)
        if (k.name == name) {
            kind = k.kind;
            return true;
        }
    return false;
}

void write_csv(const fs::path& path, std::ostream& out) {
    kind_info(read_header(path).kind).write_csv(path, out);
}

} // namespace radfmt
