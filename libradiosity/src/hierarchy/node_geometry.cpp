#include "hierarchy/node_geometry.hpp"

#include "formfactor/sampling.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>

namespace rad::hierarchy {

namespace {
// Two planar nodes on one plane make a planar parent; two parts of one surface, one surface.
NodeGeometry merged(const NodeGeometry& a, const NodeGeometry& b, double tolerance) {
    NodeGeometry out;
    out.area = a.area + b.area;
    out.box = a.box;
    out.box.add(b.box.lo);
    out.box.add(b.box.hi);
    out.centroid = out.area > 0 ? (a.centroid * a.area + b.centroid * b.area) * (1 / out.area)
                                : (a.centroid + b.centroid) * 0.5;
    out.emits = a.emits || b.emits;
    out.planar = a.planar && b.planar && dot(a.normal, b.normal) > 1 - 1e-9 &&
                 std::abs(a.offset - b.offset) <= tolerance;
    out.normal = a.normal;
    out.offset = a.offset;
    out.one_surface = a.one_surface && b.one_surface && a.surface == b.surface;
    out.surface = a.surface;
    return out;
}
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// How many of the ascending values[0, size) are at or below `target` (std::upper_bound's
// place) without a branch on them: the oracle draws its points at random places of the
// node, so the branches of a binary search were mispredicted half the time.
std::uint32_t last_at_or_before(const double* values, std::uint32_t size, double target) {
    const double* first = values;
    while (size > 1) {
        const std::uint32_t half = size / 2;
        first += half * static_cast<std::uint32_t>(first[half - 1] <= target);
        size -= half;
    }
    return static_cast<std::uint32_t>(first - values) + (size == 1 && *first <= target);
}

double polygon_area(std::span<const Vec3> polygon) {
    Vec3 sum{0, 0, 0};
    for (std::size_t k = 0; k + 2 < polygon.size(); ++k)
        sum = sum + cross(polygon[k + 1] - polygon[0], polygon[k + 2] - polygon[0]);
    return 0.5 * length(sum);
}

// The convex hull of points on the plane with unit normal `normal`, as 3D points.
std::vector<Vec3> planar_hull(const std::vector<Vec3>& points, const Vec3& normal) {
    const Vec3 u = orthogonal(normal), v = cross(normal, u);
    const Vec3 origin = points.front();
    std::vector<Kernel::Point_2> flat, hull;
    for (const auto& p : points) flat.emplace_back(dot(p - origin, u), dot(p - origin, v));
    CGAL::convex_hull_2(flat.begin(), flat.end(), std::back_inserter(hull));
    std::vector<Vec3> out;
    for (const auto& h : hull) out.push_back(origin + u * h.x() + v * h.y());
    return out;
}
} // namespace

NodeGeometries::NodeGeometries(const radfmt::MeshData& mesh,
                               const std::vector<PatchPolygon>& polygons,
                               const radfmt::LinkData& tree, const std::vector<bool>& emitter,
                               const std::vector<std::uint32_t>& surface)
    : mesh_(mesh), polygons_(polygons), tree_(tree), nodes_(tree.nodes.size()) {
    tolerance_ = 1e-9 * bounds(mesh.vertices).diagonal();
    add_leaf_patches();
    area_before_.assign(tree.leaf_order.size() + 1, 0.0);
    for (std::size_t k = 0; k < tree.leaf_order.size(); ++k)
        area_before_[k + 1] = area_before_[k] + mesh.patches[tree.leaf_order[k]].area;
    outline_start_.assign(tree.nodes.size(), 0);
    outline_size_.assign(tree.nodes.size(), 0);
    // Children come after their parents: from the last node back, children are done first.
    for (std::size_t i = tree.nodes.size(); i-- > 0;) {
        const auto& n = tree.nodes[i];
        if (n.left != radfmt::kNoNode) {
            nodes_[i] = merged(nodes_[n.left], nodes_[n.right], tolerance_);
        } else {
            const auto& patch = mesh.patches[tree.leaf_order[n.first]];
            auto& leaf = nodes_[i];
            leaf.area = patch.area;
            leaf.centroid = patch.centroid;
            for (const auto& corner : polygons[tree.leaf_order[n.first]].points())
                leaf.box.add(corner);
            leaf.planar = true;
            leaf.emits = emitter[patch.material];
            leaf.normal = patch.normal;
            leaf.offset = dot(patch.normal, patch.centroid);
            leaf.one_surface = true;
            leaf.surface = surface[tree.leaf_order[n.first]];
        }
        add_outline(static_cast<std::uint32_t>(i));
    }
}

void NodeGeometries::add_leaf_patches() {
    const auto& order = tree_.leaf_order;
    leaf_start_.assign(order.size() + 1, 0);
    leaf_normal_.reserve(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        const auto points = polygons_[order[k]].points();
        leaf_points_.insert(leaf_points_.end(), points.begin(), points.end());
        leaf_start_[k + 1] = static_cast<std::uint32_t>(leaf_points_.size());
        leaf_normal_.push_back(mesh_.patches[order[k]].normal);
        const auto cdf = ff::fan_cdf(points);
        leaf_cdf_.insert(leaf_cdf_.end(), cdf.begin(), cdf.end());
    }
}

// A leaf's outline is its patch; a parent's the hull of its children's, kept when that hull
// has the parent's area (its patches fill it).
void NodeGeometries::add_outline(std::uint32_t node) {
    const auto& n = tree_.nodes[node];
    const auto& geometry = nodes_[node];
    if (!geometry.planar) return;
    std::vector<Vec3> polygon;
    if (n.left == radfmt::kNoNode) {
        const auto points = polygons_[tree_.leaf_order[n.first]].points();
        polygon.assign(points.begin(), points.end());
    } else {
        if (outline_size_[n.left] == 0 || outline_size_[n.right] == 0) return;
        std::vector<Vec3> corners;
        for (const auto child : {n.left, n.right})
            for (const auto& p : outline(child)) corners.push_back(p);
        polygon = planar_hull(corners, geometry.normal);
    }
    if (polygon.size() < 3 || polygon.size() > kMaxOutline ||
        std::abs(polygon_area(polygon) - geometry.area) > 1e-6 * geometry.area)
        return;
    outline_start_[node] = static_cast<std::uint32_t>(outline_points_.size());
    outline_size_[node] = static_cast<std::uint8_t>(polygon.size());
    outline_points_.insert(outline_points_.end(), polygon.begin(), polygon.end());
}

NodePoint NodeGeometries::point(std::uint32_t node, double u, double v, double w) const {
    const auto& n = tree_.nodes[node];
    const double lo = area_before_[n.first], hi = area_before_[n.first + n.count];
    const double target = lo + u * (hi - lo);
    // The last patch that starts at or before the target.
    const auto k =
        n.first + last_at_or_before(area_before_.data() + n.first + 1, n.count - 1, target);
    const std::uint32_t start = leaf_start_[k], count = leaf_start_[k + 1] - start;
    const std::span<const Vec3> points(leaf_points_.data() + start, count);
    // w picks the fan triangle by area, then serves again within it.
    const std::span<const double> cdf(leaf_cdf_.data() + start - 2 * k, count - 2);
    double within = 0;
    const auto triangle = ff::pick_fan_triangle(cdf, w, &within);
    return {ff::fan_triangle_point(points, triangle, v, within), leaf_normal_[k]};
}

bool NodeGeometries::all_behind(std::uint32_t a, std::uint32_t b) const {
    const auto& plane = nodes_[a];
    if (!plane.planar) return false;
    const auto& box = nodes_[b].box;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{(corner & 1) ? box.hi[0] : box.lo[0], (corner & 2) ? box.hi[1] : box.lo[1],
                     (corner & 4) ? box.hi[2] : box.lo[2]};
        if (dot(plane.normal, p) - plane.offset > tolerance_) return false;
    }
    return true;
}

} // namespace rad::hierarchy
