// Step 2 of subdivide: every edge's number of segments, agreed between the elements on it.
#include "mesh/patches/subdivide_parts.hpp"
#include "radiosity/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace rad::subdivision {

namespace {

// Edges numbered once; each element's limit marked on its edges, and the edges a grid ties
// together united. Returns the edges' limits.
std::vector<double> tie_edges(const std::vector<Element>& elements, const Scene& scene,
                              const SubdivisionOptions& options, EdgeCounts& counts) {
    std::unordered_map<Edge, std::size_t> edge_index;
    auto edge_of = [&](std::uint32_t a, std::uint32_t b) {
        auto [it, inserted] = edge_index.try_emplace(edge_key(a, b), counts.edges.size());
        if (inserted) counts.edges.push_back(edge_key(a, b));
        return it->second;
    };
    counts.element_edges.resize(elements.size());
    for (std::size_t f = 0; f < elements.size(); ++f) {
        const auto& e = elements[f];
        for (int k = 0; k < e.corners; ++k)
            counts.element_edges[f][k] = edge_of(e.v[k], e.v[(k + 1) % e.corners]);
    }
    std::vector<double> edge_limit(counts.edges.size(), 0);
    counts.element_limit.assign(elements.size(), 0);
    counts.classes = UnionFind(counts.edges.size());
    for (std::size_t f = 0; f < elements.size(); ++f) {
        const auto& e = elements[f];
        const auto& ee = counts.element_edges[f];
        const auto& group = scene.groups[e.group];
        double limit = limit_for(options.max_edge_by_group, group, options.max_edge);
        if (e.banded) {
            // A banded triangle meets an area limit through its edge length: its patches
            // are about as high as they are long, so about half a square.
            const double area_limit = limit_for(options.max_area_by_group, group, options.max_area);
            if (area_limit > 0) {
                const double side = std::sqrt(2 * area_limit);
                limit = limit > 0 ? std::min(limit, side) : side;
            }
            counts.element_limit[f] = limit;
        }
        for (int k = 0; k < e.corners; ++k)
            if (limit > 0 && (edge_limit[ee[k]] == 0 || limit < edge_limit[ee[k]]))
                edge_limit[ee[k]] = limit;
        if (e.banded) {
            // Each edge keeps its own count: none is tied to the others.
        } else if (e.corners == 4) {
            counts.classes.unite(ee[0], ee[2]);
            counts.classes.unite(ee[1], ee[3]);
        } else {
            counts.classes.unite(ee[0], ee[1]);
            counts.classes.unite(ee[1], ee[2]);
        }
    }
    return edge_limit;
}

} // namespace

// What the limits will cost, estimated before anything is made: about one patch per half
// square of the edge limit (or per area limit) plus one per edge segment of the outline.
// Counts are computed in double, so absurd limits cannot overflow.
void check_estimate(const std::vector<Element>& elements, const Scene& scene,
                    const SubdivisionOptions& options) {
    double estimate = 0;
    for (const auto& e : elements) {
        const auto& group = scene.groups[e.group];
        const double edge = limit_for(options.max_edge_by_group, group, options.max_edge);
        const double area = limit_for(options.max_area_by_group, group, options.max_area);
        double perimeter = 0;
        for (int k = 0; k < e.corners; ++k)
            perimeter += length(scene.vertices[e.v[(k + 1) % e.corners]] - scene.vertices[e.v[k]]);
        double pieces = 1;
        if (edge > 0) pieces = std::max(pieces, e.area / (0.5 * edge * edge) + perimeter / edge);
        if (area > 0) pieces = std::max(pieces, e.area / area);
        estimate += pieces;
    }
    if (!(estimate <= options.max_patches)) {
        char text[160];
        std::snprintf(text, sizeof text, "about %.3g patches, more than --max-patches %.3g",
                      estimate, options.max_patches);
        throw InputError(scene.path + ": these limits (--max-edge, --max-area) would make " + text +
                         " (use larger limits, or raise --max-patches)");
    }
}

bool without_limits(const SubdivisionOptions& options) {
    return options.max_edge <= 0 && options.max_area <= 0 && options.max_edge_by_group.empty() &&
           options.max_area_by_group.empty();
}

namespace {

// One element's counts raised to meet its area limit; false when they already do.
bool raise_for_area(const Element& e, const std::array<std::size_t, 4>& ee, double limit,
                    EdgeCounts& counts, const Scene& scene) {
    auto& a = counts.segments[counts.classes.find(ee[0])];
    auto& b = counts.segments[counts.classes.find(ee[1])];
    const double pieces = e.corners == 4 ? double(a) * double(b) : double(a) * double(a);
    if (e.area / pieces <= limit * (1 + 1e-9)) return false;
    const double needed = e.area / limit;
    if (e.corners == 3 || &a == &b) {
        a = static_cast<std::size_t>(std::ceil(std::sqrt(needed) - 1e-9));
        return true;
    }
    // Jump to just under square patches of the limit's area, then add one piece at a time
    // along the direction whose patches are longest: the fewest patches that meet the limit,
    // in passes that do not grow with how many are needed.
    const auto& p = scene.vertices;
    const double u = 0.5 * (length(p[e.v[1]] - p[e.v[0]]) + length(p[e.v[2]] - p[e.v[3]]));
    const double v = 0.5 * (length(p[e.v[3]] - p[e.v[0]]) + length(p[e.v[2]] - p[e.v[1]]));
    const double side = std::sqrt(limit);
    const auto a0 = a, b0 = b;
    a = std::max(a, static_cast<std::size_t>(std::floor(u / side)));
    b = std::max(b, static_cast<std::size_t>(std::floor(v / side)));
    if (a == a0 && b == b0) (u / double(a) >= v / double(b) ? a : b) += 1;
    return true;
}

} // namespace

EdgeCounts agree_edge_counts(const std::vector<Element>& elements, const Scene& scene,
                             const SubdivisionOptions& options) {
    EdgeCounts counts;
    const auto edge_limit = tie_edges(elements, scene, options, counts);
    check_estimate(elements, scene, options);
    counts.segments.assign(counts.edges.size(), 1);
    for (std::size_t i = 0; i < counts.edges.size(); ++i) {
        if (edge_limit[i] <= 0) continue;
        const auto a = static_cast<std::uint32_t>(counts.edges[i] >> 32),
                   b = static_cast<std::uint32_t>(counts.edges[i]);
        const double len = length(scene.vertices[a] - scene.vertices[b]);
        auto& s = counts.segments[counts.classes.find(i)];
        s = std::max(s, static_cast<std::size_t>(std::ceil(len / edge_limit[i] - 1e-9)));
    }
    // Area limits raise counts until every element's patches are small enough; counts only
    // grow, so this settles.
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t f = 0; f < elements.size(); ++f) {
            const auto& e = elements[f];
            const double limit =
                limit_for(options.max_area_by_group, scene.groups[e.group], options.max_area);
            if (limit <= 0 || e.banded) continue;
            changed |= raise_for_area(e, counts.element_edges[f], limit, counts, scene);
        }
    }
    return counts;
}

} // namespace rad::subdivision
