// A region's thickness: the diameter of the largest circle inside it.
//
// The shorter side of the minimum-area rectangle calls a picture frame of 3 cm strips as wide
// as the picture; the inscribed circle sees the strips. Found as the pole of inaccessibility
// is (Agafonkin's polylabel): square probes over the outline's box, best bound first, each
// split while it might hold a point farther from the outline than the best found.
#include "polygon2d.hpp"
#include "regions.hpp"

#include <algorithm>
#include <cmath>
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

class OutlineDistance {
  public:
    OutlineDistance(const Region& region, const Points& points) : region_(region) {
        for (const auto& [a, b] : region.outline)
            sides_.push_back(
                {region.plane.to_2d(points.position[a]), region.plane.to_2d(points.position[b])});
    }
    const std::vector<std::array<Point2d, 2>>& sides() const { return sides_; }
    Probe probe(const Point2d& centre, double half) const {
        double d = 1e300;
        for (const auto& [a, b] : sides_) d = std::min(d, segment_distance(centre, a, b));
        if (!region_.contains(Point2(centre[0], centre[1]))) d = -d;
        return {centre, half, d};
    }

  private:
    const Region& region_;
    std::vector<std::array<Point2d, 2>> sides_;
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
    const double side = std::min(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(side > 0)) return 0;
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

std::vector<double> local_thickness(const Region& region, const Points& points,
                                    const radfmt::MeshData& mesh, std::size_t first) {
    const OutlineDistance distance(region, points);
    // Candidate disks: centred on the patches' centroids and their edges' midpoints, as large
    // as the outline lets them be.
    std::vector<Probe> disks;
    auto add = [&](const Vec3& p) {
        const auto xy = region.plane.to_2d(p);
        const auto probe = distance.probe({xy[0], xy[1]}, 0);
        if (probe.distance > 0) disks.push_back(probe);
    };
    for (std::size_t k = first; k < mesh.patches.size(); ++k) {
        const auto& patch = mesh.patches[k];
        add(patch.centroid);
        const int n = patch.corner_count();
        for (int c = 0; c < n; ++c)
            add((points.position[patch.corners[c]] + points.position[patch.corners[(c + 1) % n]]) *
                0.5);
    }
    std::vector<double> thickness;
    for (std::size_t k = first; k < mesh.patches.size(); ++k) {
        const auto xy = region.plane.to_2d(mesh.patches[k].centroid);
        double widest = 0;
        for (const auto& disk : disks)
            if (std::hypot(xy[0] - disk.centre[0], xy[1] - disk.centre[1]) <= disk.distance)
                widest = std::max(widest, 2 * disk.distance);
        thickness.push_back(widest);
    }
    return thickness;
}

} // namespace rad::surfaces
