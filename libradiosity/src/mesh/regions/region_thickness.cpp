// A region's thickness: the diameter of the largest circle inside it.
//
// The shorter side of the minimum-area rectangle calls a picture frame of 3 cm strips as wide
// as the picture; the inscribed circle sees the strips. Found as the pole of inaccessibility
// is (Agafonkin's polylabel): square probes over the outline's box, best bound first, each
// split while it might hold a point farther from the outline than the best found.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/geometry/square_index.hpp"
#include "mesh/regions/regions.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <queue>

namespace rad::surfaces {

namespace {

struct Probe {
    Point2d centre{};
    double half = 0;     // half its side
    double distance = 0; // from the centre to the outline, negative outside the region
    double bound() const { return distance + half * std::sqrt(2.0); }
    bool operator<(const Probe& other) const { return bound() < other.bound(); }
};

// The distance from a point of the plane to the region's outline. The sides are in an AABB
// tree (as 3D segments at z = 0: CGAL 5.5's tree is 3D only): probing every side was
// quadratic on a finely drawn rim (a disc of 20,000 slivers took 14 s in the summary alone).
class OutlineDistance {
  public:
    OutlineDistance(const Region& region, const Points& points) : region_(region) {
        for (const auto& [a, b] : region.outline) {
            const auto p = region.plane.to_2d(points.position[a]);
            const auto q = region.plane.to_2d(points.position[b]);
            sides_.push_back({p, q});
            if (p != q) segments_.emplace_back(Point3(p[0], p[1], 0), Point3(q[0], q[1], 0));
        }
        if (segments_.size() <= kFewSides) return;
        tree_.insert(segments_.begin(), segments_.end());
        tree_.build();
        tree_.accelerate_distance_queries();
    }
    const std::vector<std::array<Point2d, 2>>& sides() const { return sides_; }
    Probe probe(const Point2d& centre, double half) const {
        double d = 1e300;
        if (segments_.size() <= kFewSides) {
            for (const auto& [a, b] : sides_) d = std::min(d, segment_distance(centre, a, b));
        } else { // the nearest side by the tree, its distance as everywhere in the mesh stage
            const auto nearest = tree_.closest_point_and_primitive(Point3(centre[0], centre[1], 0));
            const auto& s = *nearest.second;
            d = segment_distance(centre, {s.source().x(), s.source().y()},
                                 {s.target().x(), s.target().y()});
        }
        if (!region_.contains(Point2(centre[0], centre[1]))) d = -d;
        return {centre, half, d};
    }

  private:
    static constexpr std::size_t kFewSides = 64; // tried one by one: faster than the tree
    using Kernel = CGAL::Simple_cartesian<double>;
    using Point3 = Kernel::Point_3;
    using Segments = std::vector<Kernel::Segment_3>;
    using Primitive = CGAL::AABB_segment_primitive<Kernel, Segments::const_iterator>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
    const Region& region_;
    std::vector<std::array<Point2d, 2>> sides_;
    Segments segments_;
    Tree tree_;
};

} // namespace

double region_thickness(const Region& region, const Points& points, double enough,
                        double precision) {
    const OutlineDistance distance(region, points);
    if (distance.sides().empty()) return 0;
    Point2d lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const auto& side : distance.sides())
        for (const auto& p : side)
            for (int c = 0; c < 2; ++c)
                lo[c] = std::min(lo[c], p[c]), hi[c] = std::max(hi[c], p[c]);
    const double shorter = std::min(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(shorter > 0)) return 0;
    // Squares of the box's shorter side to start with, but no more than 256 along it: a
    // triangle of rounding 2e-7 by 2 (the living room has such) made 8 million of them.
    const double side = std::max(shorter, std::max(hi[0] - lo[0], hi[1] - lo[1]) / 256);
    std::priority_queue<Probe> queue;
    Probe best = distance.probe({(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2}, 0);
    for (double x = lo[0]; x < hi[0]; x += side)
        for (double y = lo[1]; y < hi[1]; y += side)
            queue.push(distance.probe({x + side / 2, y + side / 2}, side / 2));
    // Enough probes for any outline of a game map; past that the best so far stands.
    for (int probes = 0; !queue.empty() && probes < 20000; ++probes) {
        const Probe p = queue.top();
        queue.pop();
        if (p.distance > best.distance) best = p;
        if (2 * best.distance >= enough || p.bound() - best.distance <= precision) break;
        const double h = p.half / 2;
        for (const double dx : {-h, h})
            for (const double dy : {-h, h})
                queue.push(distance.probe({p.centre[0] + dx, p.centre[1] + dy}, h));
    }
    return std::max(0.0, 2 * best.distance);
}

} // namespace rad::surfaces

namespace rad::surfaces {

namespace {

// Candidate disks of one region's patches, found by the patches' centroids in squares of a
// cell: a disk holding a point of a region no wider than a cell there is centred within one
// cell of it, and its patch's centroid within two.
class PatchDisks {
  public:
    PatchDisks(const Region& region, const Points& points, const radfmt::MeshData& mesh,
               std::size_t first)
        : distance_(region, points), region_(region), points_(points), mesh_(mesh), first_(first),
          disks_(mesh.patches.size() - first), by_square_(region.cell) {
        for (std::size_t k = first; k < mesh.patches.size(); ++k) {
            const auto xy = centroid_xy(k);
            by_square_.insert(xy, xy, static_cast<std::uint32_t>(k));
        }
        by_square_.freeze();
    }
    // The widest candidate disk that holds patch k's centroid (0: none), or the first found at
    // least `enough` wide.
    double widest_at(std::size_t k, double enough) {
        const auto xy = centroid_xy(k);
        double widest = 0;
        by_square_.find_near(xy, 2, [&](std::uint32_t patch) {
            for (const auto& disk : disks_of(patch)) {
                const double dx = xy[0] - disk.centre[0], dy = xy[1] - disk.centre[1];
                if (dx * dx + dy * dy <= disk.distance * disk.distance)
                    widest = std::max(widest, 2 * disk.distance);
            }
            return widest >= enough;
        });
        return widest;
    }

  private:
    Point2d centroid_xy(std::size_t k) const {
        const auto xy = region_.plane.to_2d(mesh_.patches[k].centroid);
        return {xy[0], xy[1]};
    }
    // Disks centred on patch k's centroid and its edges' midpoints, as large as the outline
    // lets them be (computed once, when first asked for).
    const std::vector<Probe>& disks_of(std::size_t k) {
        auto& disks = disks_[k - first_];
        if (disks) return *disks;
        disks.emplace();
        auto add = [&](const Vec3& p) {
            const auto xy = region_.plane.to_2d(p);
            const auto probe = distance_.probe({xy[0], xy[1]}, 0);
            if (probe.distance > 0) disks->push_back(probe);
        };
        const auto& patch = mesh_.patches[k];
        add(patch.centroid);
        const auto corners = mesh_.corners(patch);
        for (std::size_t c = 0; c < corners.size(); ++c)
            add((points_.position[corners[c]] +
                 points_.position[corners[(c + 1) % corners.size()]]) *
                0.5);
        return *disks;
    }
    OutlineDistance distance_;
    const Region& region_;
    const Points& points_;
    const radfmt::MeshData& mesh_;
    std::size_t first_;
    std::vector<std::optional<std::vector<Probe>>> disks_;
    SquareIndex by_square_; // the patches by their centroids' squares of a cell
};

// Whether a circle of radius r inside the region holds `point`: iff some centre within r of
// the point lies r or more from the outline, inside (a larger circle holding it holds such a
// one, centred on the way from the point to its own centre). Branch and bound over squares
// around the point: the distance is 1-Lipschitz, so a square's centre bounds its points' by its
// half diagonal. Squares under `precision` that cannot tell count as no, as does a search past
// 20,000 probes (neither seen on the fixtures).
bool circle_holds(const OutlineDistance& distance, const Point2d& point, double r,
                  double precision) {
    std::priority_queue<Probe> queue;
    queue.push(distance.probe(point, r));
    for (int probes = 0; !queue.empty() && probes < 20000; ++probes) {
        const Probe p = queue.top();
        queue.pop();
        const double dx = p.centre[0] - point[0], dy = p.centre[1] - point[1];
        if (dx * dx + dy * dy <= r * r && p.distance >= r) return true;
        if (p.bound() < r) return false; // no square left can reach r
        if (p.half < precision) continue;
        const double h = p.half / 2;
        for (const double ox : {-h, h})
            for (const double oy : {-h, h}) {
                const Point2d c{p.centre[0] + ox, p.centre[1] + oy};
                const double ex = std::max(0.0, std::abs(c[0] - point[0]) - h),
                             ey = std::max(0.0, std::abs(c[1] - point[1]) - h);
                if (ex * ex + ey * ey <= r * r) // it may hold a centre within r
                    queue.push(distance.probe(c, h));
            }
    }
    return false;
}

} // namespace

std::vector<double> local_thickness(const Region& region, const Points& points,
                                    const radfmt::MeshData& mesh, std::size_t first,
                                    const std::vector<bool>& wanted, double enough) {
    std::vector<double> thickness(mesh.patches.size() - first, 1e300);
    if (!(region.cell > 0)) return thickness;
    PatchDisks disks(region, points, mesh, first);
    for (std::size_t k = first; k < mesh.patches.size(); ++k)
        if (wanted.empty() || wanted[k - first]) thickness[k - first] = disks.widest_at(k, enough);
    return thickness;
}

std::vector<bool> held_by_circle(const Region& region, const Points& points,
                                 const radfmt::MeshData& mesh, std::size_t first, double diameter) {
    std::vector<bool> held(mesh.patches.size() - first, true);
    if (!(diameter > 0)) return held;
    const OutlineDistance distance(region, points);
    if (distance.sides().empty()) return held;
    for (std::size_t k = first; k < mesh.patches.size(); ++k) {
        const auto xy = region.plane.to_2d(mesh.patches[k].centroid);
        held[k - first] = circle_holds(distance, {xy[0], xy[1]}, diameter / 2, diameter / 20000);
    }
    return held;
}

} // namespace rad::surfaces
