// Where the layout puts each luminaire against the scene: none past what the ray tracer can
// follow, and a word for each outside the scene's bounds.
#include "radiosity/error.hpp"
#include "radiosity/luminaires.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rad {

namespace {
// How far outside a box a point lies (0 inside).
double distance_outside(const Box& box, const Vec3& p) {
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = std::max({box.lo[c] - p[c], 0.0, p[c] - box.hi[c]});
    return std::hypot(d[0], d[1], d[2]); // no overflow at 1e300
}
} // namespace

std::vector<std::string> luminaire_position_warnings(const LuminaireSet& set, const Box& scene,
                                                     const std::string& layout_name) {
    std::vector<std::string> out;
    const double size = scene.diagonal();
    // A scene with no depth (a floor alone) has its lamps outside its box by design.
    const double thinnest =
        std::min({scene.hi[0] - scene.lo[0], scene.hi[1] - scene.lo[1], scene.hi[2] - scene.lo[2]});
    for (const auto& l : set.luminaires) {
        const double away = distance_outside(scene, l.position);
        if (away <= 0.01 * size) continue;
        char text[300];
        if (!(away <= kMaxLuminaireDistance * size)) {
            std::snprintf(text, sizeof text,
                          "luminaire '%s' at (%.4g, %.4g, %.4g) lies %.3g units outside the scene, "
                          "which is %.3g across: more than %.0f times its size, where its light "
                          "cannot be traced (check its x, y, z and the layout's unit)",
                          l.name.c_str(), l.position[0], l.position[1], l.position[2], away, size,
                          kMaxLuminaireDistance);
            throw InputError(FileLoc{layout_name, l.line}, text);
        }
        if (thinnest < 0.01 * size) continue;
        std::snprintf(text, sizeof text,
                      ":%d: luminaire '%s' at (%.4g, %.4g, %.4g) lies %.3g units outside the "
                      "scene's bounds (%.4g, %.4g, %.4g) to (%.4g, %.4g, %.4g): its light reaches "
                      "the scene only from outside (check its x, y, z)",
                      l.line, l.name.c_str(), l.position[0], l.position[1], l.position[2], away,
                      scene.lo[0], scene.lo[1], scene.lo[2], scene.hi[0], scene.hi[1], scene.hi[2]);
        out.push_back(layout_name + text);
    }
    return out;
}

} // namespace rad
