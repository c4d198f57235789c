// Pass 3c of mesh_surfaces: outline pieces split where a region's band needs them.
//
// A region's band is meshed without splitting its outline pieces (they are shared with the
// regions on the other side), so a piece that a bad triangle's circumcentre encroaches leaves
// that triangle bad. Here each region is gridded on trial; for each bad triangle the piece it
// lies on, or else the piece its circumcentre encroaches (Ruppert's rule), is split at its
// middle for every region that has it (a quadrilateral region so split is gridded as a
// general one). The outline stays shared (no T-vertices), and the next
// trial of those regions meshes the band with shorter pieces.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/geometry/square_index.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_set>

namespace rad::surfaces {

namespace {

// The outline piece to halve for a bad band triangle: the longest of its own edges that is a
// piece, else the longest piece its circumcentre encroaches; 0 when none is at least twice
// `shortest` long.
EdgeKey piece_to_split(const Region& region, const std::unordered_set<EdgeKey>& pieces,
                       const SquareIndex& circles, const Points& points,
                       const radfmt::Patch& triangle, double shortest) {
    std::array<XY, 3> xy;
    for (int k = 0; k < 3; ++k) xy[k] = region.plane.to_2d(points.position[triangle.corners[k]]);
    auto longer = [&](std::uint32_t a, std::uint32_t b) {
        return length(points.position[a] - points.position[b]) >= 2 * shortest;
    };
    EdgeKey best = 0;
    double best_length = 0;
    for (int k = 0; k < 3; ++k) {
        const auto a = triangle.corners[k], b = triangle.corners[(k + 1) % 3];
        const double len = length(points.position[a] - points.position[b]);
        if (pieces.count(edge_key(a, b)) && longer(a, b) && len > best_length)
            best = edge_key(a, b), best_length = len;
    }
    if (best) return best;
    // The circumcentre, and the pieces whose diametral circle holds it.
    const double ax = xy[1][0] - xy[0][0], ay = xy[1][1] - xy[0][1], bx = xy[2][0] - xy[0][0],
                 by = xy[2][1] - xy[0][1];
    const double d = 2 * (ax * by - ay * bx);
    if (!(std::abs(d) > 0)) return 0;
    const double ux = (by * (ax * ax + ay * ay) - ay * (bx * bx + by * by)) / d,
                 uy = (ax * (bx * bx + by * by) - bx * (ax * ax + ay * ay)) / d;
    const XY centre{xy[0][0] + ux, xy[0][1] + uy};
    // Only the pieces whose circle's box holds the centre, in the outline's order.
    circles.find_near({centre[0], centre[1]}, 0, [&](std::uint32_t k) {
        const auto [a, b] = region.pieces[k];
        const auto pa = region.plane.to_2d(points.position[a]),
                   pb = region.plane.to_2d(points.position[b]);
        const XY mid{(pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2};
        const double radius = std::hypot(pb[0] - pa[0], pb[1] - pa[1]) / 2;
        if (std::hypot(centre[0] - mid[0], centre[1] - mid[1]) < radius && longer(a, b) &&
            2 * radius > best_length)
            best = edge_key(a, b), best_length = 2 * radius;
        return false;
    });
    return best;
}

// The region's pieces by the squares (of a cell) that their diametral circles' boxes touch:
// trying every piece for every bad triangle was quadratic on a finely drawn outline (a star
// of 1,000 points took 13 s here).
SquareIndex piece_circles(const Region& region, const Points& points) {
    SquareIndex circles(region.cell);
    for (std::uint32_t k = 0; k < region.pieces.size(); ++k) {
        const auto [a, b] = region.pieces[k];
        const auto pa = region.plane.to_2d(points.position[a]),
                   pb = region.plane.to_2d(points.position[b]);
        const double radius = std::hypot(pb[0] - pa[0], pb[1] - pa[1]) / 2;
        const Point2d mid{(pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2};
        circles.insert({mid[0] - radius, mid[1] - radius}, {mid[0] + radius, mid[1] + radius}, k);
    }
    circles.freeze();
    return circles;
}

// The pieces a trial grid of the region leaves bad triangles against.
void find_pieces_to_split(const Region& region, Points& points, double tolerance,
                          std::set<EdgeKey>& split) {
    const auto kept = points.position.size();
    radfmt::MeshData trial;
    SurfaceReport ignored;
    grid_region(region, points, trial, ignored, tolerance);
    std::unordered_set<EdgeKey> pieces;
    for (const auto& [a, b] : region.pieces) pieces.insert(edge_key(a, b));
    const auto circles = piece_circles(region, points);
    // Halving stops at a tenth of a cell: well-shaped triangles beside shorter pieces would be
    // specks. A sliver left beside a piece too short to halve is joined with its neighbour into
    // a quad (join_triangles) where that makes one of good shape.
    const double shortest = region.cell / 10;
    for (const auto& patch : trial.patches) {
        if (patch.corner_count() != 3 || patch_aspect(points.position, patch) <= 3) continue;
        if (const auto key = piece_to_split(region, pieces, circles, points, patch, shortest))
            split.insert(key);
    }
    points.position.resize(kept); // the trial's own points are not kept
}

// Each piece in `split` replaced by its two halves, in every region that has it; returns the
// regions changed.
std::vector<bool> halve_pieces(std::vector<Region>& regions, Points& points,
                               const std::set<EdgeKey>& split) {
    std::map<EdgeKey, std::uint32_t> middle;
    for (const auto key : split) {
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
        middle[key] = points.add((points.position[a] + points.position[b]) * 0.5);
    }
    std::vector<bool> changed(regions.size(), false);
    for (std::size_t r = 0; r < regions.size(); ++r) {
        std::vector<std::array<std::uint32_t, 2>> pieces;
        for (const auto& [a, b] : regions[r].pieces) {
            const auto it = middle.find(edge_key(a, b));
            if (it == middle.end()) {
                pieces.push_back({a, b});
                continue;
            }
            pieces.push_back({a, it->second});
            pieces.push_back({it->second, b});
            changed[r] = true;
        }
        if (!changed[r]) continue;
        regions[r].pieces = std::move(pieces);
        regions[r].quad_sides.clear(); // its sides no longer evenly split: a general region
    }
    return changed;
}

} // namespace

std::size_t refine_outline_pieces(std::vector<Region>& regions, Points& points, double tolerance,
                                  int rounds) {
    std::size_t added = 0;
    std::vector<bool> trial(regions.size(), true);
    for (int round = 0; round < rounds; ++round) {
        std::set<EdgeKey> split; // ordered: the same points whatever the order found
        for (std::size_t r = 0; r < regions.size(); ++r)
            if (trial[r] && regions[r].cell > 0 && regions[r].quad_sides.empty() &&
                width_class(regions[r].cell, regions[r].width) !=
                    WidthClass::Thin) // slivers anyway
                find_pieces_to_split(regions[r], points, tolerance, split);
        if (split.empty()) break;
        added += split.size();
        trial = halve_pieces(regions, points, split);
    }
    return added;
}

} // namespace rad::surfaces
