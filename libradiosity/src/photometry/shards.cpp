// Shards of a luminaires file: rows computed apart (rad-ff --luminaires --rows) merged into the
// .lum one run would have written.
#include "radfmt/chain.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/luminaires.hpp"

#include <algorithm>

namespace rad {

std::uint64_t merge_luminaire_parts(const std::vector<std::string>& paths,
                                    const std::string& output) {
    if (paths.empty()) throw InputError("--merge needs the part files to merge");
    const auto kind = radfmt::Kind::Luminaires;
    std::vector<radfmt::Header> headers;
    std::vector<RowPart> cover;
    for (const auto& path : paths) {
        headers.push_back(radfmt::read_header(path, &kind));
        if (!headers.back().find("rows_begin"))
            throw InputError(path + " is a whole luminaires file, not a part (rad-ff --rows)");
        cover.push_back({path, part_row(headers.back(), "rows_begin", path),
                         part_row(headers.back(), "rows_end", path)});
    }
    const auto& first = headers.front();
    const auto part_only = [](const std::string& key) {
        return key == "rows_begin" || key == "rows_end" || key == "unsharded_command";
    };
    for (std::size_t k = 0; k < headers.size(); ++k) {
        const auto& h = headers[k];
        auto same = h.tool == first.tool && h.inputs.size() == first.inputs.size();
        for (std::size_t i = 0; same && i < h.inputs.size(); ++i)
            same = h.inputs[i].hash == first.inputs[i].hash;
        for (const auto& [key, value] : first.fields)
            if (same && !part_only(key)) same = h.find(key) && *h.find(key) == value;
        same = same && h.get("unsharded_command", paths[k]) ==
                           first.get("unsharded_command", paths.front());
        if (!same)
            throw InputError(paths[k] + " and " + paths.front() +
                             " are parts of different luminaires files (other mesh, layout, "
                             "photometric files or options): compute every part alike");
    }
    radfmt::LuminaireData merged;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        auto part = radfmt::read_luminaires(paths[k]);
        if (k == 0) {
            merged = part;
            std::fill(merged.irradiance.begin(), merged.irradiance.end(), radfmt::Rgb{});
            require_row_cover(cover, merged.patch_count);
        }
        const std::size_t groups = merged.groups.size();
        if (part.patch_count != merged.patch_count || part.groups != merged.groups)
            throw InputError(paths[k] + ": changed while it was merged");
        std::copy(part.irradiance.begin() + long(cover[k].begin * groups),
                  part.irradiance.begin() + long(cover[k].end * groups),
                  merged.irradiance.begin() + long(cover[k].begin * groups));
    }
    auto header = first;
    header.version = 0;
    header.command = merged_command(first, paths.front(), output);
    std::erase_if(header.fields, [&](const auto& f) { return part_only(f.first); });
    radfmt::write_luminaires(output, header, merged);
    return merged.patch_count;
}

} // namespace rad
