// Pass 4's very last step: a speck that no triangle or quad can take (beside a notch or a
// step of the input's outline, well-shaped triangles must be specks) joins a neighbour as one
// polygon patch.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rad::surfaces {

namespace {

constexpr std::size_t kNoPatch = ~std::size_t(0);

// Past this many corners a polygon is a shape no patch should be: the speck stays.
constexpr std::size_t kMaxPolygonCorners = 12;

// The region's patches by directed side (a -> b as the patch winds): not an EdgeKey, whose
// smaller point comes first, since a side and its neighbour's are the two directions.
using PatchesBySide = std::unordered_map<std::uint64_t, std::size_t>;

std::uint64_t directed(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t(a) << 32) | b;
}

void add_sides(PatchesBySide& by_side, std::span<const std::uint32_t> corners, std::size_t patch) {
    for (std::size_t k = 0; k < corners.size(); ++k)
        by_side[directed(corners[k], corners[(k + 1) % corners.size()])] = patch;
}

void remove_sides(PatchesBySide& by_side, std::span<const std::uint32_t> corners) {
    for (std::size_t k = 0; k < corners.size(); ++k)
        by_side.erase(directed(corners[k], corners[(k + 1) % corners.size()]));
}

// The outline of `keep` and `speck` joined across the speck's side a -> b (keep's b -> a),
// counter-clockwise: keep's corners from a round to b, then the speck's from after b to before
// a. Empty when they share more than those two corners (the join would pinch or hold a hole).
std::vector<std::uint32_t> joined_outline(std::span<const std::uint32_t> keep,
                                          std::span<const std::uint32_t> speck, std::uint32_t a,
                                          std::uint32_t b) {
    const auto at = [](std::span<const std::uint32_t> list, std::uint32_t v) {
        return static_cast<std::size_t>(std::find(list.begin(), list.end(), v) - list.begin());
    };
    std::vector<std::uint32_t> out;
    for (std::size_t k = at(keep, a); out.empty() || out.back() != b; k = (k + 1) % keep.size())
        out.push_back(keep[k]);
    for (std::size_t k = (at(speck, b) + 1) % speck.size(); speck[k] != a;
         k = (k + 1) % speck.size())
        out.push_back(speck[k]);
    std::vector<std::uint32_t> sorted = out;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};
    return out;
}

// The corner from which the polygon's fan covers it with the fattest thinnest triangle (every
// fan triangle wound counter-clockwise or flat), or the polygon's size when there is none.
std::size_t fan_apex(const std::vector<XY>& p) {
    const std::size_t n = p.size();
    double total = 0;
    for (std::size_t k = 1; k + 1 < n; ++k) total += cross2(p[0], p[k], p[k + 1]);
    std::size_t best = n;
    double best_thinnest = -1e-12 * total;
    for (std::size_t c = 0; c < n; ++c) {
        double thinnest = 1e300;
        for (std::size_t k = 1; k + 1 < n; ++k)
            thinnest = std::min(thinnest, cross2(p[c], p[(c + k) % n], p[(c + k + 1) % n]));
        if (thinnest > best_thinnest) best = c, best_thinnest = thinnest;
    }
    return best;
}

struct Join {
    std::size_t partner = kNoPatch;
    std::vector<std::uint32_t> outline; // counter-clockwise from the fan's apex
    double aspect = 1e300;
    bool speck = true;
};

// The best neighbour for speck s to join: one whose joined outline is star-shaped from a
// corner, preferring a join that is no speck, then the lowest diameter^2 / (2 x area).
Join best_join(const Region& region, const Points& points, const radfmt::MeshData& mesh,
               std::size_t s, const PatchesBySide& by_side) {
    Join best;
    const auto corners = mesh.corners(s);
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const std::uint32_t a = corners[k], b = corners[(k + 1) % corners.size()];
        const auto it = by_side.find(directed(b, a));
        if (it == by_side.end()) continue;
        auto outline = joined_outline(mesh.corners(it->second), corners, a, b);
        if (outline.empty() || outline.size() > kMaxPolygonCorners) continue;
        std::vector<XY> p;
        for (const auto v : outline) p.push_back(region.plane.to_2d(points.position[v]));
        const auto apex = fan_apex(p);
        if (apex == p.size()) continue;
        std::rotate(outline.begin(), outline.begin() + std::ptrdiff_t(apex), outline.end());
        const double area = mesh.patches[s].area + mesh.patches[it->second].area;
        double diameter = 0, longest = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            for (std::size_t j = i + 1; j < p.size(); ++j)
                diameter = std::max(diameter, std::hypot(p[j][0] - p[i][0], p[j][1] - p[i][1]));
            const auto& q = p[(i + 1) % p.size()];
            longest = std::max(longest, std::hypot(q[0] - p[i][0], q[1] - p[i][1]));
        }
        const Join join{it->second, std::move(outline), diameter * diameter / (2 * area),
                        longest < region.cell / 10};
        if (std::tie(join.speck, join.aspect) < std::tie(best.speck, best.aspect))
            best = std::move(join);
    }
    return best;
}

// Patch `keep` becomes the join of itself and speck `s`: a quad when that is four corners
// strictly convex, else a polygon.
void apply_join(const Region& region, const Points& points, radfmt::MeshData& mesh, std::size_t s,
                const Join& join) {
    auto& keep = mesh.patches[join.partner];
    const auto& speck = mesh.patches[s];
    const double area = keep.area + speck.area;
    keep.centroid = (keep.centroid * keep.area + speck.centroid * speck.area) * (1 / area);
    keep.area = area;
    bool quad = join.outline.size() == 4;
    for (std::size_t k = 0; k < 4 && quad; ++k) {
        const auto& o = join.outline;
        const auto at = [&](std::size_t i) {
            return region.plane.to_2d(points.position[o[i % 4]]);
        };
        quad = cross2(at(k), at(k + 1), at(k + 2)) > 1e-9 * area;
    }
    mesh.set_corners(keep, join.outline, !quad);
}

} // namespace

std::size_t merge_specks(const Region& region, const Points& points, radfmt::MeshData& mesh,
                         std::size_t first, const std::vector<WidthClass>& classes) {
    if (!(region.cell > 0)) return 0;
    const std::size_t n = mesh.patches.size();
    auto joinable = [&](std::size_t s) {
        return classes[s] != WidthClass::Thin &&
               is_speck(points.position, mesh.patches[s], region.cell, mesh.polygon_corners);
    };
    // Most regions have none: no map of their sides (a grid of 10^7 cells would need gigabytes).
    bool any = false;
    for (std::size_t s = first; s < n && !any; ++s) any = joinable(s);
    if (!any) return 0;
    PatchesBySide by_side;
    std::vector<char> gone(n, 0);
    for (std::size_t i = first; i < n; ++i) add_sides(by_side, mesh.corners(i), i);
    std::size_t merged = 0;
    // A speck may join a speck, and the join be one still: a few rounds.
    for (bool again = true; again;) {
        again = false;
        for (std::size_t s = first; s < n; ++s) {
            if (gone[s] || !joinable(s)) continue;
            const auto join = best_join(region, points, mesh, s, by_side);
            if (join.partner == kNoPatch) continue;
            remove_sides(by_side, mesh.corners(s));
            remove_sides(by_side, mesh.corners(join.partner));
            apply_join(region, points, mesh, s, join);
            add_sides(by_side, mesh.corners(join.partner), join.partner);
            gone[s] = 1;
            ++merged;
            again = again || join.speck;
        }
    }
    std::size_t to = first;
    for (std::size_t i = first; i < n; ++i)
        if (!gone[i]) mesh.patches[to++] = mesh.patches[i];
    mesh.patches.resize(to);
    return merged;
}

} // namespace rad::surfaces
