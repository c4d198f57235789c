// Bands of rad-shade's image (rad-shade --rows, then --merge): each part is an OpenEXR file
// of the whole image's size holding only its rows, with the band's coverage and back-face
// shares in a layer of their own and what the merge needs in attributes named
// "radiosity:part-*"; the merge assembles the image one run would have rendered.
#pragma once
#include "radiosity/raster.hpp"

#include <map>
#include <string>
#include <vector>

namespace rad {

// Blacks out the rows outside `band` (their colour, coverage and back faces) and counts the
// covered and back-facing pixels of the band alone.
void keep_rows(Image& image, RowBand band);

// What a part carries besides its pixels.
struct ImagePartInfo {
    RowBand band;
    // The attributes one run writes (its command in the provenance with the output a
    // placeholder, see unsharded_command).
    std::map<std::string, std::string> attributes;
    double exposure = 0;     // the run's exposure, 0 when it comes from the whole image
    bool mark_backs = false; // --backfaces mark
    std::string png;         // the --png one run writes, or empty
};

void write_image_part(const std::string& path, const Image& band_image, const ImagePartInfo& info);

struct MergedImage {
    Image image;
    ImagePartInfo info; // band: the whole image; attributes: one run's, output in place
};
// Reads the parts: every row exactly once (InputError naming the rows in no part, with the
// --rows that computes them, or in two), of one run (same size and attributes); the
// output placeholder in the provenance becomes `output`.
MergedImage merge_image_parts(const std::vector<std::string>& paths, const std::string& output);

} // namespace rad
