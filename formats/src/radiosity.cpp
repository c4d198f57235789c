// The radiosity kind: its writer and reader, and its CSV and summary for rad-info.
#include "radfmt/kinds.hpp"
#include "radfmt/names.hpp"

#include "body_checks.hpp"
#include "compact_rows.hpp"
#include "kind_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ostream>

namespace radfmt {
namespace fs = std::filesystem;
using detail::require_count;

void write_radiosity(const fs::path& path, Header header, const RadiosityData& rad) {
    header.kind = Kind::Radiosity;
    header.set("patches", std::to_string(rad.radiosity.size()));
    if (rad.group_radiosity.size() != rad.radiosity.size() * rad.group_names.size())
        throw std::logic_error("radiosity written with a group array of the wrong size");
    if (!rad.group_names.empty()) {
        std::string names;
        for (const auto& g : rad.group_names) names += (names.empty() ? "" : ",") + g;
        header.set("light_groups", names);
    }
    BodyWriter w;
    w.u64(rad.radiosity.size());
    w.array(rad.radiosity);
    w.u64(rad.group_names.size());
    for (const auto& g : rad.group_names) w.string(g);
    w.array(rad.group_radiosity);
    write_file(path, std::move(header), w);
}

RadiosityData read_radiosity(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Radiosity;
    BodyReader r(path, &kind);
    RadiosityData rad;
    const auto n = r.count(24, "patches");
    rad.radiosity = r.array<Rgb>(n, "radiosity");
    if (r.header().version >= 2) {
        const auto groups = r.count(8, "light groups");
        rad.group_names = detail::read_group_names(r, groups);
        if (groups > 0 && n > (std::uint64_t(1) << 40) / groups)
            r.fail("too many light groups for the patches");
        rad.group_radiosity = r.array<Rgb>(n * groups, "light group radiosity");
    }
    r.expect_end();
    require_count(r.header(), "patches", n, r);
    for (const auto* values : {&rad.radiosity, &rad.group_radiosity})
        for (std::size_t i = 0; i < values->size(); ++i)
            for (int c = 0; c < 3; ++c)
                if (!((*values)[i][c] >= 0 && std::isfinite((*values)[i][c])))
                    r.fail("radiosity value " + std::to_string(i) + " is negative or not finite");
    if (header_out) *header_out = r.take_header();
    return rad;
}

namespace detail {
void radiosity_csv(const fs::path& path, std::ostream& out) {
    const auto rad = read_radiosity(path);
    char line[160];
    if (rad.group_count() == 0) {
        out << "patch,b_r,b_g,b_b\n";
        for (std::size_t i = 0; i < rad.radiosity.size(); ++i) {
            const auto& b = rad.radiosity[i];
            std::snprintf(line, sizeof line, "%zu,%.10g,%.10g,%.10g\n", i, b[0], b[1], b[2]);
            out << line;
            if (!out) return;
        }
        return;
    }
    // With light groups: one row per patch and group.
    out << "patch,group,b_r,b_g,b_b\n";
    detail::write_group_rows(out, rad.group_names, rad.group_radiosity);
}

std::string radiosity_summary(const fs::path& path, Header& header) {
    const auto rad = read_radiosity(path, &header);
    std::string text = std::to_string(rad.radiosity.size()) + " patches";
    if (rad.group_count()) {
        text += ", " + std::to_string(rad.group_count()) + " light group(s):";
        // A sky's hundreds of groups: the first few and the last.
        const auto& names = rad.group_names;
        for (std::size_t k = 0; k < names.size(); ++k) {
            if (names.size() > 12 && k == 10) {
                text += " ... " + names.back();
                break;
            }
            text += " " + names[k];
        }
    }
    return text;
}
} // namespace detail

} // namespace radfmt
