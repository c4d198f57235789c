// Faces written twice: exporters repeat faces (McGuire's CornellBox-Original has each box's
// "bottom" face repeat one of its sides). Two patches on one spot would each take half the
// light and hide each other, so the repeats are dropped and reported.
#include "radiosity/scene.hpp"
#include "weld.hpp"

#include <algorithm>
#include <map>

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

std::uint64_t hash_of(const std::vector<std::uint32_t>& key) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL ^ key.size();
    for (const auto k : key) {
        h ^= k + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
        h *= 0xbf58476d1ce4e5b9ULL;
        h ^= h >> 31;
    }
    return h;
}

// For each face, the first face with its key (itself when it is the first): faces sorted by
// a hash of their keys, equal hashes compared key by key (a map keyed by the corner lists
// costs a node and two allocations a face).
std::vector<std::size_t> first_with_key(const Scene& scene, const std::vector<std::uint32_t>& id) {
    const std::size_t n = scene.polygons.size();
    std::vector<std::pair<std::uint64_t, std::size_t>> by_hash(n);
    for (std::size_t f = 0; f < n; ++f) by_hash[f] = {hash_of(cycle_key(scene.polygons[f], id)), f};
    std::sort(by_hash.begin(), by_hash.end());
    std::vector<std::size_t> first(n);
    for (std::size_t f = 0; f < n; ++f) first[f] = f;
    for (std::size_t a = 0; a < n;) {
        std::size_t b = a + 1;
        while (b < n && by_hash[b].first == by_hash[a].first) ++b;
        for (std::size_t x = a + 1; x < b; ++x) { // ascending faces: the first match is earliest
            const auto key = cycle_key(scene.polygons[by_hash[x].second], id);
            for (std::size_t y = a; y < x; ++y)
                if (first[by_hash[y].second] == by_hash[y].second &&
                    cycle_key(scene.polygons[by_hash[y].second], id) == key) {
                    first[by_hash[x].second] = by_hash[y].second;
                    break;
                }
        }
        a = b;
    }
    return first;
}

} // namespace

DuplicateFaces remove_duplicate_faces(Scene& scene) {
    const auto first = first_with_key(scene, weld_by_position(scene.vertices));
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
