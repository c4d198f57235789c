// Shards of a luminaires file: rows computed apart (rad-ff --luminaires --rows) merged into the
// .lum one run would have written.
#include "radfmt/chain.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/luminaires.hpp"

#include <algorithm>

namespace rad {

std::uint64_t merge_luminaire_parts(const std::vector<std::string>& paths,
                                    const std::string& output) {
    std::vector<radfmt::Header> headers;
    const auto cover =
        patch_row_parts(paths, radfmt::Kind::Luminaires, "luminaires files", headers);
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
    radfmt::write_luminaires(output, merged_part_header(headers.front(), paths.front(), output),
                             merged);
    return merged.patch_count;
}

} // namespace rad
