// Pass 3a of mesh_surfaces: short outline pieces merged across points a region does not need.
//
// Runs give every region along an edge every point on it, so no region has a T-vertex. But a
// game map's brushes put points a unit apart along a wall's foot (the corners of the trims and
// floor tiles across it), and a region's band cannot be meshed into well-shaped patches against
// a piece that short without specks. Where a point lies on a straight stretch of the region's
// outline, and every other region at it is one that crease smoothing never mixes with (another
// material or group, or a normal over kCreaseDegrees away), the region leaves the point out:
// the T-vertex it leaves is on a boundary that shading does not smooth across.
#include "regions.hpp"

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

// Whether crease smoothing never mixes the two regions' patches.
bool never_smoothed_together(const Region& a, const Region& b) {
    const double cos_crease = std::cos(kCreaseDegrees * std::numbers::pi / 180);
    return a.material != b.material || a.group != b.group ||
           dot(a.plane.normal, b.plane.normal) < cos_crease;
}

// For each point, the regions whose pieces end at it (sorted, once each).
std::unordered_map<std::uint32_t, std::vector<std::uint32_t>>
regions_at_points(const std::vector<Region>& regions) {
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> at;
    for (std::uint32_t r = 0; r < regions.size(); ++r) // in order: each list comes sorted
        for (const auto& piece : regions[r].pieces)
            for (const auto p : piece) {
                auto& list = at[p];
                if (list.empty() || list.back() != r) list.push_back(r);
            }
    return at;
}

// One region's pieces with their ends' neighbours: merges two pieces meeting at a point.
class PieceChain {
  public:
    PieceChain(const Region& region, const Points& points, double tolerance)
        : pieces_(region.pieces), alive_(region.pieces.size(), true), points_(points),
          tolerance_(tolerance) {
        for (std::size_t k = 0; k < pieces_.size(); ++k)
            for (const auto p : pieces_[k]) at_[p].push_back(k);
    }
    std::size_t size() const { return pieces_.size(); }
    double length_of(std::size_t k) const {
        return length(points_.position[pieces_[k][1]] - points_.position[pieces_[k][0]]);
    }
    const std::array<std::uint32_t, 2>& piece(std::size_t k) const { return pieces_[k]; }
    // The piece across point p from piece k, when p is a straight point between exactly two.
    std::optional<std::size_t> straight_neighbour(std::size_t k, std::uint32_t p) const {
        const auto& list = at_.at(p);
        std::size_t other = k, live = 0;
        for (const auto q : list)
            if (alive_[q]) ++live, other = q != k ? q : other;
        if (live != 2 || other == k) return std::nullopt;
        const auto a = far_end(k, p), b = far_end(other, p);
        const Vec3 pa = points_.position[a], pb = points_.position[b], pp = points_.position[p];
        const Vec3 d = pb - pa;
        const double len = length(d);
        if (!(len > 0) || dot(pp - pa, d) <= 0 || dot(pp - pb, d) >= 0) return std::nullopt;
        if (length(cross(pp - pa, d)) / len > tolerance_) return std::nullopt;
        return other;
    }
    std::uint32_t far_end(std::size_t k, std::uint32_t p) const {
        return pieces_[k][0] == p ? pieces_[k][1] : pieces_[k][0];
    }
    // Pieces k and other (meeting at p) become one; returns its index.
    std::size_t merge(std::size_t k, std::size_t other, std::uint32_t p) {
        const std::array<std::uint32_t, 2> joined{far_end(k, p), far_end(other, p)};
        alive_[k] = alive_[other] = false;
        pieces_.push_back(joined);
        alive_.push_back(true);
        for (const auto q : joined) at_[q].push_back(pieces_.size() - 1);
        return pieces_.size() - 1;
    }
    std::vector<std::array<std::uint32_t, 2>> live_pieces() const {
        std::vector<std::array<std::uint32_t, 2>> out;
        for (std::size_t k = 0; k < pieces_.size(); ++k)
            if (alive_[k]) out.push_back(pieces_[k]);
        return out;
    }

  private:
    std::vector<std::array<std::uint32_t, 2>> pieces_;
    std::vector<bool> alive_;
    std::unordered_map<std::uint32_t, std::vector<std::size_t>> at_;
    const Points& points_;
    double tolerance_;
};

// Shortest first, each piece under a tenth of a cell merged with its straight neighbour across a
// point the region may leave out, the shorter merge first, while the result stays within the
// region's piece length. Returns the points left out.
std::size_t relax_region(Region& region, std::uint32_t self, const std::vector<Region>& regions,
                         const std::unordered_map<std::uint32_t, std::vector<std::uint32_t>>& at,
                         const Points& points, double tolerance) {
    const double gap = region.cell / 10;
    auto may_leave = [&](std::uint32_t p) {
        for (const auto r : at.at(p))
            if (r != self && !never_smoothed_together(region, regions[r])) return false;
        return true;
    };
    PieceChain chain(region, points, tolerance);
    std::set<std::pair<double, std::size_t>> short_pieces;
    for (std::size_t k = 0; k < chain.size(); ++k)
        if (chain.length_of(k) < gap) short_pieces.emplace(chain.length_of(k), k);
    std::size_t left_out = 0;
    while (!short_pieces.empty()) {
        const auto k = short_pieces.begin()->second;
        short_pieces.erase(short_pieces.begin());
        double best_length = region.piece * (1 + 1e-9);
        std::optional<std::pair<std::size_t, std::uint32_t>> best;
        for (const auto p : chain.piece(k)) {
            const auto other = chain.straight_neighbour(k, p);
            if (!other || !may_leave(p)) continue;
            const double joined = chain.length_of(k) + chain.length_of(*other);
            if (joined <= best_length) best_length = joined, best = std::pair{*other, p};
        }
        if (!best) continue;
        short_pieces.erase({chain.length_of(best->first), best->first});
        const auto joined = chain.merge(k, best->first, best->second);
        ++left_out;
        if (chain.length_of(joined) < gap) short_pieces.emplace(chain.length_of(joined), joined);
    }
    if (left_out) region.pieces = chain.live_pieces();
    return left_out;
}

} // namespace

std::size_t relax_outline_points(std::vector<Region>& regions, const Points& points,
                                 double tolerance) {
    const auto at = regions_at_points(regions);
    std::size_t left_out = 0;
    for (std::uint32_t r = 0; r < regions.size(); ++r) {
        auto& region = regions[r];
        // Quadrilateral regions' sides are evenly split runs, already as long as they may be.
        if (!(region.piece > 0) || !region.quad_sides.empty()) continue;
        left_out += relax_region(region, r, regions, at, points, tolerance);
    }
    return left_out;
}

} // namespace rad::surfaces
