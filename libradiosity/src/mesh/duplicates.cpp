// Faces written twice: exporters repeat faces (McGuire's CornellBox-Original has each box's
// "bottom" face repeat one of its sides). Two patches on one spot would each take half the
// light and hide each other, so the repeats are dropped and reported.
#include "radiosity/scene.hpp"
#include "weld.hpp"

#include <algorithm>
#include <map>

namespace rad {

DuplicateFaces remove_duplicate_faces(Scene& scene) {
    const auto id = weld_by_position(scene.vertices);
    // A face's key: its welded corners as a cycle, rotated to start at the smallest id, so
    // the same face written from another corner matches; the reverse cycle (the same spot
    // seen from the other side, a two-sided surface) does not.
    std::map<std::vector<std::uint32_t>, std::size_t> first_with;
    DuplicateFaces report;
    std::vector<Polygon> kept;
    kept.reserve(scene.polygons.size());
    for (std::size_t f = 0; f < scene.polygons.size(); ++f) {
        std::vector<std::uint32_t> key;
        for (auto v : scene.polygons[f].vertices) key.push_back(id[v]);
        if (!key.empty())
            std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
        const auto [it, added] = first_with.try_emplace(std::move(key), f);
        if (added) {
            kept.push_back(std::move(scene.polygons[f]));
            continue;
        }
        report.lines.emplace_back(scene.polygons[f].line, scene.polygons[it->second].line);
        if (report.removed++ == 0) {
            report.first_line = scene.polygons[f].line;
            report.first_original_line = scene.polygons[it->second].line;
        }
    }
    scene.polygons = std::move(kept);
    return report;
}

} // namespace rad
