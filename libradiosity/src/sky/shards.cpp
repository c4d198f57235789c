// Shards of a sky-view file: rows computed apart (rad-ff --sky --rows) merged into the .sky
// one run would have written.
#include "radfmt/chain.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"

#include <algorithm>

namespace rad {

std::uint64_t merge_sky_parts(const std::vector<std::string>& paths, const std::string& output) {
    std::vector<radfmt::Header> headers;
    const auto cover = patch_row_parts(paths, radfmt::Kind::Sky, "sky files", headers);
    radfmt::SkyData merged;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        auto part = radfmt::read_sky(paths[k]);
        if (k == 0) {
            merged = part;
            std::fill(merged.coefficients.begin(), merged.coefficients.end(), 0.0f);
            require_row_cover(cover, merged.patch_count);
        }
        if (part.patch_count != merged.patch_count || part.sky_patches != merged.sky_patches)
            throw InputError(paths[k] + ": changed while it was merged");
        const std::size_t row = merged.sky_patches * 3;
        std::copy(part.coefficients.begin() + long(cover[k].begin * row),
                  part.coefficients.begin() + long(cover[k].end * row),
                  merged.coefficients.begin() + long(cover[k].begin * row));
    }
    radfmt::write_sky(output, merged_part_header(headers.front(), paths.front(), output), merged);
    return merged.patch_count;
}

} // namespace rad
