// Faces written twice: exporters repeat faces (McGuire's CornellBox-Original has each box's
// "bottom" face repeat one of its sides). Two patches on one spot would each take half the
// light and hide each other, so the repeats are dropped and reported.
#include "core/equal_keys.hpp"
#include "mesh/load/weld.hpp"
#include "radiosity/scene.hpp"

#include <algorithm>

namespace rad {

namespace {

// A face's key: its welded corners as a cycle, rotated to start at the smallest id, so the
// same face written from another corner matches; the reverse cycle (the same spot seen from
// the other side, a two-sided surface) does not.
std::vector<std::uint32_t> cycle_key(const Polygon& polygon, const std::vector<std::uint32_t>& id) {
    std::vector<std::uint32_t> key;
    for (auto v : polygon.vertices) key.push_back(id[v]);
    if (!key.empty()) std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    return key;
}

} // namespace

DuplicateFaces remove_duplicate_faces(Scene& scene) {
    const auto id = weld_by_position(scene.vertices);
    const auto first = first_with_equal_key(
        scene.polygons.size(), [&](std::size_t f) { return cycle_key(scene.polygons[f], id); });
    DuplicateFaces report;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f) {
        if (first[f] == f) continue;
        const int line = scene.polygons[f].line, original = scene.polygons[first[f]].line;
        report.lines.emplace_back(line, original);
        if (report.removed++ == 0) report.first_line = line, report.first_original_line = original;
    }
    std::size_t count = 0; // kept faces, moved down in place
    for (std::size_t f = 0; f < scene.polygons.size(); ++f)
        if (first[f] == f) {
            if (count != f) scene.polygons[count] = std::move(scene.polygons[f]);
            ++count;
        }
    scene.polygons.resize(count);
    return report;
}

} // namespace rad
