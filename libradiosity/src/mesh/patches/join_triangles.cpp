// Pass 4's last step: band triangles too small or too thin for a patch, joined with a neighbour
// into a quad.
//
// Beside an outline piece under a tenth of a cell (a step or a notch of the input), well-shaped
// triangles must be about its size (specks), and beside a piece too short to halve (pass 3c
// stops at a tenth of a cell) the mesher leaves slivers. Either, with the triangle across one of
// its sides, is often a convex quad of good shape: a patch with a short side along the detail.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rad::surfaces {

namespace {

constexpr std::size_t kNoPatch = ~std::size_t(0);

// Strictly convex: turning the same way at every corner, each turn more than rounding.
bool strictly_convex(const std::array<XY, 4>& q) {
    int sign = 0;
    for (int k = 0; k < 4; ++k) {
        const XY &a = q[k], &b = q[(k + 1) % 4], &c = q[(k + 2) % 4];
        const double turn = cross2(a, b, c);
        if (std::abs(turn) <=
            1e-9 * std::hypot(b[0] - a[0], b[1] - a[1]) * std::hypot(c[0] - b[0], c[1] - b[1]))
            return false;
        const int s = turn > 0 ? 1 : -1;
        if (sign != 0 && s != sign) return false;
        sign = s;
    }
    return true;
}

// The region's triangles by side: the one or two triangles that have each side.
using TrianglesBySide = std::unordered_map<EdgeKey, std::array<std::size_t, 2>>;

struct Join {
    std::size_t partner = kNoPatch;
    radfmt::Patch quad;
    double aspect = 3; // the worst a join may make
};

// The best join for triangle t: with a neighbour across one of its sides that is free and not a
// speck, into a strictly convex quad of the lowest aspect (at most 3).
Join best_join(const Region& region, const Points& points, const radfmt::MeshData& mesh,
               std::size_t t, const TrianglesBySide& by_side, const std::vector<char>& free,
               const std::vector<char>& speck) {
    Join best;
    const auto& c = mesh.patches[t].corners;
    for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = c[k], v = c[(k + 1) % 3], w = c[(k + 2) % 3];
        const auto& pair = by_side.at(edge_key(u, v));
        const std::size_t other = pair[0] == t ? pair[1] : pair[0];
        if (other == kNoPatch || !free[other] || speck[other]) continue;
        const auto& oc = mesh.patches[other].corners;
        const std::uint32_t x = oc[0] != u && oc[0] != v   ? oc[0]
                                : oc[1] != u && oc[1] != v ? oc[1]
                                                           : oc[2];
        radfmt::Patch quad = mesh.patches[t];
        quad.corners = {u, x, v, w}; // the side u-v gives way to the neighbour's corner
        quad.area += mesh.patches[other].area;
        quad.centroid = (mesh.patches[t].centroid * mesh.patches[t].area +
                         mesh.patches[other].centroid * mesh.patches[other].area) *
                        (1 / quad.area);
        std::array<XY, 4> q;
        for (int j = 0; j < 4; ++j) q[j] = region.plane.to_2d(points.position[quad.corners[j]]);
        if (!strictly_convex(q)) continue;
        const double aspect = patch_aspect(points.position, quad);
        if (aspect <= best.aspect) best = {other, quad, aspect};
    }
    return best;
}

} // namespace

std::size_t join_triangles(const Region& region, const Points& points, radfmt::MeshData& mesh,
                           std::size_t first) {
    if (!(region.cell > 0)) return 0;
    const std::size_t n = mesh.patches.size();
    TrianglesBySide by_side;
    std::vector<char> free(n, 0), speck(n, 0);
    std::vector<std::size_t> wanted; // specks and slivers, in the patches' order
    for (std::size_t i = first; i < n; ++i) {
        const auto& p = mesh.patches[i];
        if (p.corner_count() != 3) continue;
        free[i] = 1;
        for (int k = 0; k < 3; ++k) {
            auto [it, fresh] = by_side.try_emplace(edge_key(p.corners[k], p.corners[(k + 1) % 3]),
                                                   std::array<std::size_t, 2>{i, kNoPatch});
            if (!fresh) it->second[1] = i;
        }
        speck[i] = is_speck(points.position, p, region.cell);
        if (speck[i] || patch_aspect(points.position, p) > 3) wanted.push_back(i);
    }
    std::size_t joined = 0;
    for (const auto t : wanted) {
        if (!free[t]) continue; // already some sliver's partner
        const Join join = best_join(region, points, mesh, t, by_side, free, speck);
        if (join.partner == kNoPatch) continue;
        mesh.patches[t] = join.quad;
        free[t] = free[join.partner] = 0;
        mesh.patches[join.partner].corners[0] = kNone; // taken into the quad
        ++joined;
    }
    mesh.patches.erase(std::remove_if(mesh.patches.begin() + std::ptrdiff_t(first),
                                      mesh.patches.end(),
                                      [](const radfmt::Patch& p) { return p.corners[0] == kNone; }),
                       mesh.patches.end());
    return joined;
}

} // namespace rad::surfaces
