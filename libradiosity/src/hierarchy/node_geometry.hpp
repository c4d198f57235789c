// What the link oracle knows of each node of the patch tree: area, box, plane when its
// patches share one, and area-uniform points (internal header).
#pragma once
#include "radiosity/formfactor_method.hpp"
#include "radiosity/vec.hpp"

#include <span>
#include <vector>

namespace rad::hierarchy {

struct NodeGeometry {
    double area = 0;
    Box box;         // of its patches' corners
    Vec3 centroid{}; // of its patches' area
    bool planar = false;
    Vec3 normal{};      // when planar: every patch's normal
    double offset = 0;  // when planar: the plane dot(normal, x) = offset
    bool emits = false; // some patch of it is of a material that emits in the mesh
    // Its patches are (part of) one connected surface (connected_surfaces): it may receive
    // a link, one irradiance for all of them.
    bool one_surface = false;
    std::uint32_t surface = 0; // when one_surface: which
};

// A point of a node, with the normal of the patch it lies on.
struct NodePoint {
    Vec3 point;
    Vec3 normal;
};

class NodeGeometries {
  public:
    // `emitter`: per material, whether light from it is linked as from an emitter;
    // `surface`: per patch, its surface (connected_surfaces).
    NodeGeometries(const radfmt::MeshData& mesh, const std::vector<PatchPolygon>& polygons,
                   const radfmt::LinkData& tree, const std::vector<bool>& emitter,
                   const std::vector<std::uint32_t>& surface);
    const NodeGeometry& operator[](std::size_t node) const { return nodes_[node]; }
    // The area-uniform point of `node` for (u, v, w) in [0,1)^3: u picks the patch by area
    // (stratify it to spread points over the node), v and w the point within it.
    NodePoint point(std::uint32_t node, double u, double v, double w) const;
    // True when nothing of `b` lies strictly in front of planar node `a`'s plane.
    bool all_behind(std::uint32_t a, std::uint32_t b) const;
    // The outline of a flat node whose patches fill a convex polygon (a block of a patch
    // grid is a rectangle), so that form factors to it are one contour integral; empty when
    // its patches do not (not flat, not convex, or an outline of over kMaxOutline corners).
    std::span<const Vec3> outline(std::uint32_t node) const {
        return {outline_points_.data() + outline_start_[node], outline_size_[node]};
    }
    static constexpr std::size_t kMaxOutline = 16;

  private:
    void add_outline(std::uint32_t node);
    void add_leaf_patches();
    const radfmt::MeshData& mesh_;
    const std::vector<PatchPolygon>& polygons_;
    const radfmt::LinkData& tree_;
    std::vector<NodeGeometry> nodes_;
    std::vector<double> area_before_; // per position in leaf order (+1): the areas before it
    // What point() reads of each patch, in leaf order, so that a node's patches lie side by
    // side: drawing points on a small node reads a few lines, where each patch's polygon and
    // normal in patch order was a miss of its own (a third of point()'s time on pandora-cut).
    // Patch k (in leaf order) has corners leaf_points_[leaf_start_[k], leaf_start_[k + 1]) and
    // the fan cdf of two entries fewer, from leaf_cdf_[leaf_start_[k] - 2k].
    std::vector<Vec3> leaf_points_;
    std::vector<double> leaf_cdf_;
    std::vector<std::uint32_t> leaf_start_;
    std::vector<Vec3> leaf_normal_;
    double tolerance_ = 0; // lengths below this are rounding
    std::vector<std::uint32_t> outline_start_;
    std::vector<std::uint8_t> outline_size_;
    std::vector<Vec3> outline_points_;
};

} // namespace rad::hierarchy
