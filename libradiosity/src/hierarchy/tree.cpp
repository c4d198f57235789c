// build_patch_tree: the patches of each plane and material together, split at the median of
// their centroids, longest side first (on a surface's patch grid: blocks of 2 x 1 and 2 x 2
// patches, the pyramid over the grid); above the planes, clusters of nearby planes split the
// same way.
#include "radiosity/hierarchy.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

namespace rad {

namespace {
// Puts the lower half of ids[0, count) by position along the longest side of their
// positions' box first (ties broken by id: the same split on every run); returns the half.
template <class Position>
std::uint32_t split_at_median(std::vector<std::uint32_t>::iterator ids, std::uint32_t count,
                              const Position& position) {
    Box box;
    for (std::uint32_t k = 0; k < count; ++k) box.add(position(ids[k]));
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (box.hi[a] - box.lo[a] > box.hi[axis] - box.lo[axis]) axis = a;
    const std::uint32_t half = count / 2;
    // nth_element's order within each half is deterministic for a given input, and the
    // splits below put it in order: the tree is the same on every run.
    std::nth_element(ids, ids + half, ids + count, [&](std::uint32_t a, std::uint32_t b) {
        const double ca = position(a)[axis], cb = position(b)[axis];
        return ca < cb || (ca == cb && a < b);
    });
    return half;
}

struct TreeBuilder {
    const radfmt::MeshData& mesh;
    radfmt::LinkData& tree;
    std::vector<std::vector<std::uint32_t>> planes; // the patches of each plane
    std::vector<Vec3> plane_centre;                 // per plane: its patches' mean centroid
    std::vector<std::uint32_t> plane_order;         // planes, as the upper tree splits them
    std::uint32_t placed = 0;                       // patches put into leaf_order so far

    // Node over the planes plane_order[first, first + count), built depth first: their
    // patches go into leaf_order in the order the tree visits them.
    std::uint32_t build_planes(std::uint32_t first, std::uint32_t count) {
        if (count == 1) {
            const auto& patches = planes[plane_order[first]];
            std::copy(patches.begin(), patches.end(), tree.leaf_order.begin() + placed);
            placed += static_cast<std::uint32_t>(patches.size());
            return build(placed - static_cast<std::uint32_t>(patches.size()),
                         static_cast<std::uint32_t>(patches.size()));
        }
        const auto index = static_cast<std::uint32_t>(tree.nodes.size());
        tree.nodes.push_back({placed, 0, radfmt::kNoNode, radfmt::kNoNode});
        const std::uint32_t half = split_at_median(
            plane_order.begin() + first, count,
            [&](std::uint32_t plane) -> const Vec3& { return plane_centre[plane]; });
        const auto left = build_planes(first, half);
        const auto right = build_planes(first + half, count - half);
        auto& node = tree.nodes[index];
        node.count = placed - node.first;
        node.left = left;
        node.right = right;
        return index;
    }

    // Node for leaf_order[first, first + count), its subtree after it (depth first).
    std::uint32_t build(std::uint32_t first, std::uint32_t count) {
        const auto index = static_cast<std::uint32_t>(tree.nodes.size());
        tree.nodes.push_back({first, count, radfmt::kNoNode, radfmt::kNoNode});
        if (count == 1) return index;
        const std::uint32_t half = split_at_median(
            tree.leaf_order.begin() + first, count,
            [&](std::uint32_t patch) -> const Vec3& { return mesh.patches[patch].centroid; });
        const auto left = build(first, half);
        const auto right = build(first + half, count - half);
        tree.nodes[index].left = left;
        tree.nodes[index].right = right;
        return index;
    }
};

// The patches by material and plane (normal and offset rounded to a millionth of the
// scene's size), in order of their first patch. A material of its own keeps a lamp out of
// the blocks of the ceiling around it: a block's radiosity is its mean, and a link carries
// it as one number.
void group_by_plane(const radfmt::MeshData& mesh, TreeBuilder& builder) {
    const double size = std::max(bounds(mesh.vertices).diagonal(), 1e-300);
    std::map<std::tuple<std::uint32_t, long long, long long, long long, long long>, std::uint32_t>
        index;
    for (std::uint32_t p = 0; p < mesh.patches.size(); ++p) {
        const auto& patch = mesh.patches[p];
        auto q = [](double v, double step) {
            return static_cast<long long>(std::llround(v / step));
        };
        const auto key = std::make_tuple(patch.material, q(patch.normal[0], 1e-6),
                                         q(patch.normal[1], 1e-6), q(patch.normal[2], 1e-6),
                                         q(dot(patch.normal, patch.centroid), 1e-6 * size));
        const auto [it, added] =
            index.emplace(key, static_cast<std::uint32_t>(builder.planes.size()));
        if (added) builder.planes.emplace_back();
        builder.planes[it->second].push_back(p);
    }
    for (const auto& patches : builder.planes) {
        Vec3 sum{0, 0, 0};
        for (const auto p : patches) sum = sum + mesh.patches[p].centroid;
        builder.plane_centre.push_back(sum * (1.0 / double(patches.size())));
    }
    builder.plane_order.resize(builder.planes.size());
    std::iota(builder.plane_order.begin(), builder.plane_order.end(), 0u);
}
} // namespace

radfmt::LinkData build_patch_tree(const radfmt::MeshData& mesh) {
    radfmt::LinkData tree;
    tree.patch_count = mesh.patches.size();
    tree.leaf_order.resize(mesh.patches.size());
    std::iota(tree.leaf_order.begin(), tree.leaf_order.end(), 0u);
    if (mesh.patches.empty()) {
        tree.link_start = {0};
        return tree;
    }
    tree.nodes.reserve(2 * mesh.patches.size() - 1);
    TreeBuilder builder{mesh, tree, {}, {}, {}, 0};
    group_by_plane(mesh, builder);
    builder.build_planes(0, static_cast<std::uint32_t>(builder.planes.size()));
    tree.link_start.assign(tree.nodes.size() + 1, 0);
    return tree;
}

std::vector<double> link_row_sums(const radfmt::LinkData& links) {
    // Down the tree (parents come first): a node's sum is its parent's plus its own links.
    std::vector<double> node_sum(links.nodes.size(), 0.0);
    std::vector<double> patch_sum(links.patch_count, 0.0);
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        for (auto l = links.link_start[i]; l < links.link_start[i + 1]; ++l)
            node_sum[i] += links.factor[l];
        const auto& n = links.nodes[i];
        if (n.left == radfmt::kNoNode) {
            patch_sum[links.leaf_order[n.first]] = node_sum[i];
        } else {
            node_sum[n.left] += node_sum[i];
            node_sum[n.right] += node_sum[i];
        }
    }
    return patch_sum;
}

} // namespace rad
