// The steps of `subdivide` (internal header): faces cleaned into elements, edge segment
// counts agreed between the elements sharing an edge, then each element's patches.
#pragma once
#include "core/union_find.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace rad::subdivision {

using Edge = std::uint64_t; // two vertex indices, smaller first
inline Edge edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
}

struct Element { // a triangle or convex quad over scene vertices, ready to subdivide
    std::array<std::uint32_t, 4> v{};
    int corners = 3;
    std::uint32_t group = 0, material = 0;
    Vec3 normal{};
    double area = 0;
    // A long or thin triangle: subdivided in bands along its longest edge, each edge with
    // its own segment count, instead of the regular n x n pattern (whose n^2 patches follow
    // the longest edge: a 466 x 0.13 sliver at max-edge 10 would become 2209 patches).
    bool banded = false;
};

// The scene's faces as elements: repeated corners and degenerate faces dropped, planar
// triangles and convex quads kept, non-planar faces split into triangles (refused with
// --strict), other polygons triangulated; each counted in `report`. Throws when none is left.
std::vector<Element> make_elements(const Scene& scene, const SubdivisionOptions& options,
                                   SubdivisionReport& report);

// Every element edge numbered once, and its number of segments: the edges a grid ties
// together (a quad's opposite sides, a triangle's three) share one count, large enough for
// the edge limits of every element on them and for the area limits.
struct EdgeCounts {
    std::vector<Edge> edges;
    std::vector<std::array<std::size_t, 4>> element_edges; // by element, corner k to k + 1
    std::vector<double> element_limit; // a banded triangle's patch size (0: none)
    std::vector<std::size_t> segments; // by class representative
    UnionFind classes{0};
    std::size_t count(std::size_t edge) { return segments[classes.find(edge)]; }
};
// Throws before anything is made when the limits would make over --max-patches patches.
void check_estimate(const std::vector<Element>& elements, const Scene& scene,
                    const SubdivisionOptions& options);
// Calls check_estimate.
EdgeCounts agree_edge_counts(const std::vector<Element>& elements, const Scene& scene,
                             const SubdivisionOptions& options);

// Each element's patches over the agreed counts: quads as grids, triangles as triangle grids,
// banded triangles in bands along their longest edge; edge points shared (no T-vertices).
radfmt::MeshData make_patches(const std::vector<Element>& elements, EdgeCounts& counts,
                              const Scene& scene);
// The same with no limits (every edge one segment): one patch an element, with the vertices
// and patches make_patches would give, without numbering the edges.
radfmt::MeshData make_whole_patches(const std::vector<Element>& elements, const Scene& scene);
// Whether the options set no limit (make_whole_patches applies).
bool without_limits(const SubdivisionOptions& options);

} // namespace rad::subdivision
