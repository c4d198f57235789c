// Pass 3b of mesh_surfaces: short outline pieces merged across points a region does not need.
//
// Runs give every region along an edge every point on it, so no region has a T-vertex. But a
// game map's brushes put points a unit apart along a wall's foot (the corners of the trims and
// floor tiles across it), and a region's band cannot be meshed into well-shaped patches against
// a piece that short without specks. Where a point lies on a straight stretch of the region's
// outline, and every other region at it is one that crease smoothing never mixes with (another
// material or group, or a normal over kCreaseDegrees away), the region leaves the point out:
// the T-vertex it leaves is on a boundary that shading does not smooth across.
//
// Where the outline turns into the region (a reflex corner: the foot of a pillar, the rim of a
// pipe's hole) and everything else at the corner rises from the region's plane, the region
// may cut the corner off by up to a twentieth of a cell: the ground it gains lies under or
// inside what rises there, and the specks a short step needs are gone.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/regions/regions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <unordered_map>

namespace rad::surfaces {

namespace {

// rad-shade's default crease angle: smoothing stops at a bend sharper than this.
constexpr double kCreaseDegrees = 30;
const double kCosCrease = std::cos(kCreaseDegrees * std::numbers::pi / 180);

// Whether crease smoothing never mixes the two regions' patches.
bool never_smoothed_together(const Region& a, const Region& b) {
    return a.material != b.material || a.group != b.group ||
           dot(a.plane.normal, b.plane.normal) < kCosCrease;
}

// One region's pieces with their ends' neighbours: merges two pieces meeting at a point.
class PieceChain {
  public:
    // `walled`: for each piece, whether something rises from the region all along it.
    PieceChain(const Region& region, const Points& points, double tolerance,
               std::vector<char> walled)
        : region_(region), side_(region.pieces.size(), kUnknown), walled_(std::move(walled)),
          pieces_(region.pieces), alive_(region.pieces.size(), true), points_(points),
          tolerance_(tolerance) {
        for (std::size_t k = 0; k < pieces_.size(); ++k)
            for (const auto p : pieces_[k]) at_[p].push_back(k);
    }
    std::size_t size() const { return pieces_.size(); }
    double length_of(std::size_t k) const {
        return length(points_.position[pieces_[k][1]] - points_.position[pieces_[k][0]]);
    }
    const std::array<std::uint32_t, 2>& piece(std::size_t k) const { return pieces_[k]; }
    bool walled(std::size_t k) const { return walled_[k]; }
    // The piece across point p from piece k, when exactly two meet there.
    std::optional<std::size_t> neighbour(std::size_t k, std::uint32_t p) const {
        std::size_t other = k, live = 0;
        for (const auto q : at_.at(p))
            if (alive_[q]) ++live, other = q != k ? q : other;
        if (live != 2 || other == k) return std::nullopt;
        return other;
    }
    // Whether p lies on a straight line between the far ends of pieces k and other.
    bool straight(std::size_t k, std::size_t other, std::uint32_t p) const {
        const auto a = far_end(k, p), b = far_end(other, p);
        const Vec3 pa = points_.position[a], pb = points_.position[b], pp = points_.position[p];
        const Vec3 d = pb - pa;
        const double len = length(d);
        if (!(len > 0) || dot(pp - pa, d) <= 0 || dot(pp - pb, d) >= 0) return false;
        return length(cross(pp - pa, d)) / len <= tolerance_;
    }
    // The area of the corner that merging pieces k and other across p cuts off, when it lies
    // outside the region (p is a reflex corner), p is no further than `most` from the merged
    // piece, and no other point of the outline lies in the corner; else 0.
    double corner_cut_off(std::size_t k, std::size_t other, std::uint32_t p, double most) {
        const auto a = far_end(k, p), b = far_end(other, p);
        const int side = inside_of_walk(k, p, other);
        if (a == b || side == 0 || joined(a, b)) return 0;
        const auto pa = xy(a), pb = xy(b), pp = xy(p);
        const double chord = std::hypot(pb[0] - pa[0], pb[1] - pa[1]);
        const double turn = cross2(pa, pp, pb); // > 0: a left turn from a through p to b
        if (!(chord > 0) || !(turn * side < 0) || std::abs(turn) / chord > most) return 0;
        for (const auto& [q, list] : at_) {
            if (q == a || q == b || q == p || !live(q)) continue;
            if (inside_triangle(xy(q), pa, pp, pb)) return 0;
        }
        return std::abs(turn) / 2;
    }
    std::uint32_t far_end(std::size_t k, std::uint32_t p) const {
        return pieces_[k][0] == p ? pieces_[k][1] : pieces_[k][0];
    }
    // Pieces k and other (meeting at p) become one; returns its index. `corner`: the corner
    // cut off lies outside the region (corner_cut_off), now inside.
    std::size_t merge(std::size_t k, std::size_t other, std::uint32_t p, bool corner) {
        const std::array<std::uint32_t, 2> joined{far_end(k, p), far_end(other, p)};
        if (corner) corners_.push_back({xy(joined[0]), xy(p), xy(joined[1])});
        const int side = inside_of_walk(k, p, other);
        alive_[k] = alive_[other] = false;
        pieces_.push_back(joined);
        side_.push_back(static_cast<std::int8_t>(side));
        walled_.push_back(walled_[k] && walled_[other]);
        alive_.push_back(true);
        for (const auto q : joined) at_[q].push_back(pieces_.size() - 1);
        return pieces_.size() - 1;
    }
    double joined_length(std::size_t k, std::size_t other, std::uint32_t p) const {
        return length(points_.position[far_end(k, p)] - points_.position[far_end(other, p)]);
    }
    // The corners cut off by merges, in order.
    const std::vector<std::vector<XY>>& corners() const { return corners_; }
    std::vector<std::array<std::uint32_t, 2>> live_pieces() const {
        std::vector<std::array<std::uint32_t, 2>> out;
        for (std::size_t k = 0; k < pieces_.size(); ++k)
            if (alive_[k]) out.push_back(pieces_[k]);
        return out;
    }

  private:
    XY xy(std::uint32_t q) const { return region_.plane.to_2d(points_.position[q]); }
    bool live(std::uint32_t q) const {
        const auto& list = at_.at(q);
        return std::any_of(list.begin(), list.end(), [&](std::size_t k) { return alive_[k]; });
    }
    bool joined(std::uint32_t a, std::uint32_t b) const {
        for (const auto k : at_.at(a))
            if (alive_[k] && far_end(k, a) == b) return true;
        return false;
    }
    static bool inside_triangle(const XY& q, const XY& a, const XY& b, const XY& c) {
        const double d1 = cross2(a, b, q), d2 = cross2(b, c, q), d3 = cross2(c, a, q);
        return (d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0);
    }
    // Which side of piece k, from its first point to its second, the region lies on: 1 left,
    // -1 right, 0 not known (a point just beside its middle tells, for the input's pieces).
    int side_of(std::size_t k) {
        if (side_[k] != kUnknown) return side_[k];
        const auto a = xy(pieces_[k][0]), b = xy(pieces_[k][1]);
        const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
        const double step = std::min(0.01 * len, std::max(1e-6 * len, 10 * tolerance_));
        side_[k] = 0;
        if (len > 0) {
            const double mx = (a[0] + b[0]) / 2, my = (a[1] + b[1]) / 2;
            const bool left = region_.contains(Point2(mx - dy / len * step, my + dx / len * step));
            const bool right = region_.contains(Point2(mx + dy / len * step, my - dx / len * step));
            if (left != right) side_[k] = left ? 1 : -1;
        }
        return side_[k];
    }
    // The side the region lies on walking from piece k's far end through p along `other`
    // (0: not known, or the two pieces disagree).
    int inside_of_walk(std::size_t k, std::uint32_t p, std::size_t other) {
        const int in = pieces_[k][1] == p ? side_of(k) : -side_of(k);
        const int out = pieces_[other][0] == p ? side_of(other) : -side_of(other);
        return in == out ? in : 0;
    }
    static constexpr std::int8_t kUnknown = 2;
    const Region& region_;
    std::vector<std::vector<XY>> corners_;
    std::vector<std::int8_t> side_;
    std::vector<char> walled_;
    std::vector<std::array<std::uint32_t, 2>> pieces_;
    std::vector<bool> alive_;
    std::unordered_map<std::uint32_t, std::vector<std::size_t>> at_;
    const Points& points_;
    double tolerance_;
};

// A merge of piece k across point p with its neighbour.
struct Merge {
    std::size_t other = 0;
    std::uint32_t p = 0;
    double corner = 0; // the area cut off at a bend (0: a straight stretch)
};

// Shortest first, each piece under a tenth of a cell merged with its neighbour across a point
// the region may leave out (along a straight stretch) or cover past (at a reflex bend), the
// shorter merge first, while the result stays within the region's piece length. Returns the
// points left out along straight stretches.
std::size_t relax_region(Region& region, std::uint32_t self, const std::vector<Region>& regions,
                         const RisingWalls& walls, const Points& points, double tolerance,
                         OutlineGrowth& growth) {
    const double gap = region.cell / 10;
    auto may_leave = [&](std::uint32_t p) {
        for (const auto r : walls.regions_at(p))
            if (r != self && !never_smoothed_together(region, regions[r])) return false;
        return true;
    };
    std::vector<char> walled;
    for (const auto& [a, b] : region.pieces) walled.push_back(walls.along_piece(self, a, b));
    PieceChain chain(region, points, tolerance, std::move(walled));
    std::set<std::pair<double, std::size_t>> short_pieces;
    for (std::size_t k = 0; k < chain.size(); ++k)
        if (chain.length_of(k) < gap) short_pieces.emplace(chain.length_of(k), k);
    std::size_t left_out = 0, bends = 0;
    while (!short_pieces.empty()) {
        const auto k = short_pieces.begin()->second;
        short_pieces.erase(short_pieces.begin());
        double best_length = region.piece * (1 + 1e-9);
        std::optional<Merge> best;
        for (const auto p : chain.piece(k)) {
            const auto other = chain.neighbour(k, p);
            if (!other) continue;
            Merge merge{*other, p, 0};
            if (chain.straight(k, *other, p)) {
                if (!may_leave(p)) continue;
            } else if (!chain.walled(k) || !chain.walled(*other) || !walls.around_point(self, p) ||
                       !((merge.corner = chain.corner_cut_off(k, *other, p, gap / 2)) > 0)) {
                continue;
            }
            const double joined = chain.joined_length(k, *other, p);
            if (joined <= best_length) best_length = joined, best = merge;
        }
        if (!best) continue;
        short_pieces.erase({chain.length_of(best->other), best->other});
        const auto joined = chain.merge(k, best->other, best->p, best->corner > 0);
        if (best->corner > 0)
            ++bends, growth.area += best->corner;
        else
            ++left_out;
        if (chain.length_of(joined) < gap) short_pieces.emplace(chain.length_of(joined), joined);
    }
    if (left_out || bends) region.pieces = chain.live_pieces();
    for (const auto& corner : chain.corners()) cover(region, corner);
    if (bends) region.outline = region.pieces;
    growth.points += bends;
    return left_out;
}

} // namespace

RisingWalls::RisingWalls(const std::vector<Region>& regions) : regions_(regions) {
    for (std::uint32_t r = 0; r < regions.size(); ++r) // in order: each list comes sorted
        for (const auto& piece : regions[r].pieces) {
            for (const auto p : piece) {
                auto& list = at_point_[p];
                if (list.empty() || list.back() != r) list.push_back(r);
            }
            auto& list = at_piece_[edge_key(piece[0], piece[1])];
            if (list.empty() || list.back() != r) list.push_back(r);
        }
}

bool RisingWalls::all_rise(std::uint32_t self, const std::vector<std::uint32_t>& others) const {
    bool any = false;
    for (const auto r : others) {
        if (r == self) continue;
        if (std::abs(dot(regions_[self].plane.normal, regions_[r].plane.normal)) >= kCosCrease)
            return false;
        any = true;
    }
    return any;
}

bool RisingWalls::around_point(std::uint32_t self, std::uint32_t p) const {
    return all_rise(self, at_point_.at(p));
}

bool RisingWalls::along_piece(std::uint32_t self, std::uint32_t a, std::uint32_t b) const {
    const auto it = at_piece_.find(edge_key(a, b));
    return it != at_piece_.end() && all_rise(self, it->second);
}

std::size_t relax_outline_points(std::vector<Region>& regions, const Points& points,
                                 double tolerance, OutlineGrowth& growth) {
    const RisingWalls walls(regions);
    std::size_t left_out = 0;
    for (std::uint32_t r = 0; r < regions.size(); ++r) {
        auto& region = regions[r];
        // Quadrilateral regions' sides are evenly split runs, already as long as they may be.
        if (!(region.piece > 0) || !region.quad_sides.empty()) continue;
        left_out += relax_region(region, r, regions, walls, points, tolerance, growth);
    }
    return left_out;
}

} // namespace rad::surfaces
