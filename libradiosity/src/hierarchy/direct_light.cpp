#include "hierarchy/direct_light.hpp"

#include "radiosity/random.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad::hierarchy {

namespace {
struct LightPoint {
    NodePoint at;
    double disc = 0; // the emitters' area this point stands for
};

// kLightPoints points over the emitting leaves, stratified by area along the tree's leaf
// order.
std::vector<LightPoint> light_points(const radfmt::LinkData& tree, const NodeGeometries& geometry,
                                     std::uint64_t seed) {
    std::vector<std::uint32_t> leaves;
    std::vector<double> area_before{0.0};
    for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
        if (!tree.is_leaf(i) || !geometry[i].emits) continue;
        leaves.push_back(i);
        area_before.push_back(area_before.back() + geometry[i].area);
    }
    std::vector<LightPoint> out;
    const double total = area_before.back();
    if (!(total > 0)) return out;
    Rng rng(seed, 0x6c69676874ull); // "light"
    for (int k = 0; k < kLightPoints; ++k) {
        const double target = (k + rng.uniform()) / kLightPoints * total;
        const auto at = std::upper_bound(area_before.begin() + 1, area_before.end(), target);
        const auto leaf =
            leaves[std::min<std::size_t>(at - area_before.begin() - 1, leaves.size() - 1)];
        out.push_back(
            {geometry.point(leaf, 0.5, rng.uniform(), rng.uniform()), total / kLightPoints});
    }
    return out;
}

// The irradiance at `x` from the light points (exitance 1), each a disc of its area so that
// a point beside it stays finite.
double irradiance(const NodePoint& x, const std::vector<LightPoint>& lights,
                  const RayScene& scene) {
    double sum = 0;
    for (const auto& light : lights) {
        const Vec3 d = light.at.point - x.point;
        const double r2 = dot(d, d);
        if (!(r2 > 0)) continue;
        const double r = std::sqrt(r2);
        const double at_x = dot(x.normal, d) / r, at_light = -dot(light.at.normal, d) / r;
        if (at_x <= 0 || at_light <= 0) continue;
        if (!scene.visible(x.point, light.at.point)) continue;
        sum += light.disc * at_x * at_light / (std::numbers::pi * r2 + light.disc);
    }
    return sum;
}
} // namespace

DirectLight estimate_direct_light(const radfmt::MeshData& mesh, const radfmt::LinkData& tree,
                                  const NodeGeometries& geometry, const RayScene& scene,
                                  std::uint64_t seed) {
    DirectLight out;
    const auto lights = light_points(tree, geometry, seed);
    if (lights.empty()) return out;
    const std::size_t count = tree.nodes.size();
    // Per node, the area-weighted first and second moments of its patches' irradiance.
    std::vector<double> first(count, 0.0), second(count, 0.0);
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) {
        if (!tree.is_leaf(i)) return;
        const auto& patch = mesh.patches[tree.leaf_order[tree.nodes[i].first]];
        const double e = irradiance({patch.centroid, patch.normal}, lights, scene);
        first[i] = e;
        second[i] = e * e;
    });
    // Children come after their parents: from the last node back, children are done first.
    for (std::size_t i = count; i-- > 0;) {
        const auto& n = tree.nodes[i];
        if (n.left == radfmt::kNoNode) continue;
        const double a = geometry[i].area;
        if (!(a > 0)) continue;
        for (const auto child : {n.left, n.right}) {
            first[i] += first[child] * geometry[child].area / a;
            second[i] += second[child] * geometry[child].area / a;
        }
    }
    out.mean.assign(count, 0.0f);
    out.spread.assign(count, 0.0f);
    for (std::size_t i = 0; i < count; ++i) {
        out.mean[i] = static_cast<float>(first[i]);
        if (tree.is_leaf(i) || !(geometry[i].area > 0)) continue;
        double within = 0;
        for (const auto slot : radfmt::share_slots(tree, i)) {
            if (slot == radfmt::kNoNode) continue;
            const double variance = std::max(0.0, second[slot] - first[slot] * first[slot]);
            within += variance * geometry[slot].area / geometry[i].area;
        }
        out.spread[i] = static_cast<float>(std::sqrt(within));
    }
    out.reference = first[0];
    return out;
}

} // namespace rad::hierarchy
