// build_patch_tree: the patches of each surface (connected, on one plane, of one material)
// together, split at the median of their centroids, longest side first (on a surface's patch
// grid: blocks of 2 x 1 and 2 x 2 patches, the pyramid over the grid); above the surfaces,
// clusters of nearby surfaces split the same way.
#include "hierarchy/surfaces.hpp"
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
    std::vector<std::vector<std::uint32_t>> surfaces; // the patches of each surface
    std::vector<Vec3> surface_centre;                 // per surface: its patches' mean centroid
    std::vector<std::uint32_t> surface_order;         // surfaces, as the upper tree splits them
    std::uint32_t placed = 0;                         // patches put into leaf_order so far

    // Node over the surfaces surface_order[first, first + count), built depth first: their
    // patches go into leaf_order in the order the tree visits them.
    std::uint32_t build_surfaces(std::uint32_t first, std::uint32_t count) {
        if (count == 1) {
            const auto& patches = surfaces[surface_order[first]];
            std::copy(patches.begin(), patches.end(), tree.leaf_order.begin() + placed);
            placed += static_cast<std::uint32_t>(patches.size());
            return build(placed - static_cast<std::uint32_t>(patches.size()),
                         static_cast<std::uint32_t>(patches.size()));
        }
        const auto index = static_cast<std::uint32_t>(tree.nodes.size());
        tree.nodes.push_back({placed, 0, radfmt::kNoNode, radfmt::kNoNode});
        const std::uint32_t half = split_at_median(
            surface_order.begin() + first, count,
            [&](std::uint32_t surface) -> const Vec3& { return surface_centre[surface]; });
        const auto left = build_surfaces(first, half);
        const auto right = build_surfaces(first + half, count - half);
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

// The patches by surface (connected, one plane and material), in order of their first patch.
// A material of its own keeps a lamp out of the blocks of the ceiling around it: a block's
// radiosity is its mean, and a link carries it as one number.
void group_by_surface(const radfmt::MeshData& mesh, const std::vector<std::uint32_t>& surface,
                      TreeBuilder& builder) {
    for (std::uint32_t p = 0; p < mesh.patches.size(); ++p) {
        if (surface[p] == builder.surfaces.size()) builder.surfaces.emplace_back();
        builder.surfaces[surface[p]].push_back(p);
    }
    for (const auto& patches : builder.surfaces) {
        Vec3 sum{0, 0, 0};
        for (const auto p : patches) sum = sum + mesh.patches[p].centroid;
        builder.surface_centre.push_back(sum * (1.0 / double(patches.size())));
    }
    builder.surface_order.resize(builder.surfaces.size());
    std::iota(builder.surface_order.begin(), builder.surface_order.end(), 0u);
}
} // namespace

radfmt::LinkData hierarchy::build_surface_tree(const radfmt::MeshData& mesh,
                                               const std::vector<std::uint32_t>& surface) {
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
    group_by_surface(mesh, surface, builder);
    builder.build_surfaces(0, static_cast<std::uint32_t>(builder.surfaces.size()));
    tree.link_start.assign(tree.nodes.size() + 1, 0);
    return tree;
}

radfmt::LinkData build_patch_tree(const radfmt::MeshData& mesh) {
    return hierarchy::build_surface_tree(mesh, hierarchy::connected_surfaces(mesh));
}

std::vector<double> link_node_areas(const radfmt::MeshData& mesh, const radfmt::LinkData& links) {
    // Children come after their parents: from the last node back, a node's children are done.
    std::vector<double> area(links.nodes.size(), 0.0);
    for (std::size_t i = links.nodes.size(); i-- > 0;) {
        const auto& n = links.nodes[i];
        area[i] = n.left == radfmt::kNoNode ? mesh.patches[links.leaf_order[n.first]].area
                                            : area[n.left] + area[n.right];
    }
    return area;
}

std::vector<double> link_row_sums(const radfmt::MeshData& mesh, const radfmt::LinkData& links) {
    const auto area = link_node_areas(mesh, links);
    // Down the tree (parents come first): a node's sum is its parent's plus what links at it
    // or above it delivered to it as a part (a part's share of F over its share of the area).
    std::vector<double> node_sum(links.nodes.size(), 0.0);
    std::vector<double> patch_sum(links.patch_count, 0.0);
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        const auto slots = radfmt::share_slots(links, i);
        for (auto l = links.link_start[i]; l < links.link_start[i + 1]; ++l)
            for (int k = 0; k < 4; ++k)
                if (links.receiver_share[l][k] != 0)
                    node_sum[slots[k]] += delivered_factor(
                        links.factor[l], links.receiver_share[l][k], area[i], area[slots[k]]);
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
