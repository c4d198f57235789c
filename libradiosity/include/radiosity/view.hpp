// Cameras in Radiance's view convention.
#pragma once
#include "radiosity/error.hpp"
#include "radiosity/vec.hpp"

#include <string>

namespace rad {

// Radiance's view convention: -vp eye, -vd direction, -vu up, -vh/-vv full angles (deg).
struct View {
    Vec3 position{0, 0, 0};
    Vec3 direction{0, 0, 1};
    Vec3 up{0, 1, 0};
    double horizontal_deg = 45;
    double vertical_deg = 45;
};
// Parses "-vp x y z -vd x y z ..." (a leading "rvu" and -vtv are accepted); `source` names
// the text's origin in messages. Throws InputError for malformed or degenerate views.
View parse_view(const std::string& text, const FileLoc& source, View start = {});
View read_view_file(const std::string& path);
// The unit ray from the eye through (u, v) of the image: u from its left edge (0) to its
// right (1), v from its top (0) to its bottom (1), as the rasteriser maps them.
Vec3 view_ray(const View& view, double u, double v);

} // namespace rad
