// A bounding volume hierarchy over a gather's lights, split at the median of the longest axis.
#include "gather/light_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad::gather {

namespace {
constexpr double kPi = std::numbers::pi;
} // namespace

LightTree::LightTree(const radfmt::MeshData& mesh, std::vector<Light> lights)
    : lights_(std::move(lights)) {
    if (lights_.empty()) return;
    nodes_.reserve(2 * lights_.size());
    build(mesh, 0, static_cast<std::uint32_t>(lights_.size()));
}

namespace {
// The axis of v's largest component (the first of equals).
int largest_axis(const Vec3& v) {
    return v[0] >= v[1] && v[0] >= v[2] ? 0 : v[1] >= v[2] ? 1 : 2;
}

// The side a patch faces most: 2 x its normal's largest axis, + 1 when negative. Lights of one
// side share a narrow normal cone, so a node of them faces a point wholly or not at all.
int facing_side(const Vec3& n) {
    const int axis = largest_axis({std::abs(n[0]), std::abs(n[1]), std::abs(n[2])});
    return 2 * axis + (n[axis] < 0 ? 1 : 0);
}
} // namespace

// Reserves the node, then splits its lights: by the side they face while they face several
// (at the boundary between sides nearest the middle), then at the median centroid along the
// axis where the centroids spread most (ties by patch, so the tree is the same on every run).
std::uint32_t LightTree::build(const radfmt::MeshData& mesh, std::uint32_t first,
                               std::uint32_t count) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(summarise(mesh, first, count));
    if (count == 1) return index;
    const auto begin = lights_.begin() + first;
    auto side = [&](const Light& l) { return facing_side(mesh.patches[l.patch].normal); };
    std::uint32_t half = count / 2;
    if (std::any_of(begin, begin + count,
                    [&](const Light& l) { return side(l) != side(*begin); })) {
        std::sort(begin, begin + count, [&](const Light& a, const Light& b) {
            const int sa = side(a), sb = side(b);
            return sa != sb ? sa < sb : a.patch < b.patch;
        });
        // The boundary between two sides nearest the middle.
        std::uint32_t best = 0;
        for (std::uint32_t k = 1; k < count; ++k)
            if (side(begin[k]) != side(begin[k - 1]) &&
                (best == 0 ||
                 std::abs(int(k) - int(count / 2)) < std::abs(int(best) - int(count / 2))))
                best = k;
        half = best;
    } else {
        Box centroids;
        for (std::uint32_t i = first; i < first + count; ++i)
            centroids.add(mesh.patches[lights_[i].patch].centroid);
        const int axis = largest_axis(centroids.hi - centroids.lo);
        std::nth_element(begin, begin + half, begin + count, [&](const Light& a, const Light& b) {
            const double ca = mesh.patches[a.patch].centroid[axis];
            const double cb = mesh.patches[b.patch].centroid[axis];
            return ca != cb ? ca < cb : a.patch < b.patch;
        });
    }
    const std::uint32_t left = build(mesh, first, half);
    const std::uint32_t right = build(mesh, first + half, count - half);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
}

LightTree::Node LightTree::summarise(const radfmt::MeshData& mesh, std::uint32_t first,
                                     std::uint32_t count) const {
    Node node;
    node.first = first;
    node.count = count;
    Box box;
    Vec3 weighted_centre{0, 0, 0}, normal_sum{0, 0, 0};
    for (std::uint32_t i = first; i < first + count; ++i) {
        const auto& light = lights_[i];
        const auto& p = mesh.patches[light.patch];
        for (const auto v : mesh.corners(p)) box.add(mesh.vertices[v]);
        const double power = brightness(light.radiosity) * p.area;
        node.power += power;
        weighted_centre = weighted_centre + p.centroid * power;
        normal_sum = normal_sum + p.normal * power;
        for (int c = 0; c < 3; ++c)
            node.exitance_vector[c] =
                node.exitance_vector[c] + p.normal * (light.radiosity[c] * p.area);
    }
    node.centre = box.centre();
    node.half_extent = (box.hi - box.lo) * 0.5;
    node.radius = length(node.half_extent);
    node.centroid = node.power > 0 ? weighted_centre * (1 / node.power) : node.centre;
    node.axis = normalized(normal_sum);
    if (length(node.axis) > 0) {
        double cos_spread = 1;
        for (std::uint32_t i = first; i < first + count; ++i)
            cos_spread =
                std::min(cos_spread, dot(node.axis, mesh.patches[lights_[i].patch].normal));
        node.cos_spread = std::clamp(cos_spread, -1.0, 1.0);
        node.sin_spread = std::sqrt(1 - node.cos_spread * node.cos_spread);
    }
    return node;
}

// Sum of L_j A_j cos_j cos / (pi r^2) with every light at the node's centroid: the
// cosines at the lights are the exitance vectors' projections, exact while all face the point.
Rgb LightTree::cluster_irradiance(const Node& node, const Vec3& point, const Vec3& normal) const {
    const Vec3 d = node.centroid - point;
    const double r2 = dot(d, d);
    const Vec3 towards = d * (1 / std::sqrt(r2));
    const double cos_here = std::max(0.0, dot(normal, towards));
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = std::max(0.0, -dot(node.exitance_vector[c], towards)) * cos_here / (kPi * r2);
    return out;
}

// The normal cone (spread c about the axis) against the directions from the bounding sphere
// to the point (within b = asin(radius / distance) of w): every light faces the point when
// angle(axis, w) + c + b < pi/2, none does when angle(axis, w) - c - b >= pi/2; in cosines,
// cos angle(axis, w) above sin(c + b), or at most -sin(c + b), while c + b < pi/2.
LightTree::Facing LightTree::facing_point(const Node& node, const Vec3& w, double distance) {
    if (!(distance > node.radius)) return Facing::Some;
    const double sin_b = node.radius / distance, cos_b = std::sqrt(1 - sin_b * sin_b);
    const double cos_cb = node.cos_spread * cos_b - node.sin_spread * sin_b;
    if (cos_cb <= 0) return Facing::Some; // the cone and the sphere span a half-space
    const double sin_cb = node.sin_spread * cos_b + node.cos_spread * sin_b;
    const double cos_w = dot(node.axis, w) / distance;
    if (cos_w > sin_cb) return Facing::All;
    if (cos_w <= -sin_cb) return Facing::None;
    return Facing::Some;
}

// Visits the nodes the point might see, front to back of the tree, calling `take(node,
// all_facing, in_front, distance)`, which says whether to stop at the node (true) or open it.
template <class Take>
void LightTree::visit(const Vec3& point, const Vec3& normal, Take take) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        // The point's plane against the lights' box: wholly behind it, nothing is seen.
        const double offset = dot(normal, node.centre - point);
        const double support = std::abs(normal[0]) * node.half_extent[0] +
                               std::abs(normal[1]) * node.half_extent[1] +
                               std::abs(normal[2]) * node.half_extent[2];
        if (offset + support <= 0) continue;
        const Vec3 w = point - node.centre;
        const double distance = length(w);
        const Facing facing = facing_point(node, w, distance);
        if (facing == Facing::None) continue;
        if (!take(node, facing == Facing::All, offset - support > 0, distance)) {
            stack[top++] = node.right;
            stack[top++] = node.left;
        }
    }
}

void LightTree::cut(const Vec3& point, const Vec3& normal, double max_ratio, Cut& out,
                    double tolerance) const {
    out.lights.clear();
    out.clusters.clear();
    visit(point, normal, [&](const Node& node, bool all_facing, bool in_front, double distance) {
        const auto index = static_cast<std::uint32_t>(&node - nodes_.data());
        if (all_facing && in_front && node.radius < max_ratio * distance) {
            out.clusters.push_back({index, cluster_irradiance(node, point, normal)});
            return true;
        }
        if (tolerance > 0 && node.radius < kLooseRatio * distance) {
            const Rgb e = cluster_irradiance(node, point, normal);
            const double ratio = node.radius / distance;
            // Wholly in front and facing: the estimate's error is about e x ratio^2. Else
            // (some lights face away, or lie behind the point's plane) it can be all of what
            // the node could give, at most its power over pi (distance - radius)^2.
            const double gap = distance - node.radius;
            const double error = all_facing && in_front ? brightness(e) * ratio * ratio
                                                        : node.power / (kPi * gap * gap);
            if (error <= tolerance) {
                out.clusters.push_back({index, e});
                return true;
            }
        }
        if (node.count > 1) return false;
        out.lights.push_back(node.first);
        return true;
    });
}

double LightTree::rough_irradiance(const Vec3& point, const Vec3& normal) const {
    double total = 0;
    visit(point, normal, [&](const Node& node, bool all_facing, bool in_front, double distance) {
        (void)all_facing, (void)in_front; // a rough sum: facing or not, as the estimate says
        if (!(node.radius < kLooseRatio * distance) && node.count > 1) return false;
        double e = brightness(cluster_irradiance(node, point, normal));
        if (node.count == 1) e = std::min(e, brightness(lights_[node.first].radiosity));
        total += e;
        return true;
    });
    return total;
}

const Light& LightTree::pick(std::uint32_t index, double u, double* remainder) const {
    while (nodes_[index].count > 1) {
        const Node& node = nodes_[index];
        const double left = nodes_[node.left].power, right = nodes_[node.right].power;
        const double share = left + right > 0 ? left / (left + right) : 0.5;
        if (u < share) {
            u = share > 0 ? u / share : 0;
            index = node.left;
        } else {
            u = share < 1 ? (u - share) / (1 - share) : 0;
            index = node.right;
        }
        u = std::min(u, std::nextafter(1.0, 0.0));
    }
    if (remainder) *remainder = u;
    return lights_[nodes_[index].first];
}

} // namespace rad::gather
