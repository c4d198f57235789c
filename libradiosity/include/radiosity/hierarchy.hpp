// Hierarchical form factors (rad-ff --method hierarchical): Hanrahan, Salzman and Aupperle's
// hierarchical radiosity with clusters above the surfaces (Smits et al., Sillion). A binary
// tree over the patches (a patch grid splits into blocks, blocks of nearby surfaces into
// clusters) and links between its nodes, refined top down by a geometric oracle, so the links
// depend on geometry alone and are cached like a form-factor matrix.
#pragma once
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rad {

// A link carries light into node i from node j when F_ij, the share of i's view that j
// fills (grown by up to 5x when i's patches face j unevenly, and up to 2x when visibility
// varies across the pair), is at most epsilon (a 64th of it when j holds an emitter), and F_ij
// times how much the emitters' direct light varies inside j's parts is at most a 50th of
// epsilon times the light i gets; else a node is split. On the Cornell box at 5120 patches
// (bench/hierarchical), 2e-2 gives about 44 links a patch (1/56 of the analytic matrix's
// non-zeros), every surface's mean within 0.2% of the analytic solution and 1.6% rms per
// patch (each link's shares carry its light to and from the quarters of its nodes); 1e-2
// about 75 (1/33), 0.12% and 1.2%.
inline constexpr double kDefaultLinkEpsilon = 2e-2;
inline constexpr int kDefaultLinkSamples = 64;

struct HierarchyOptions {
    double epsilon = kDefaultLinkEpsilon;
    // Per link between blocks or clusters: sample pairs, each with a visibility ray (a link
    // between two patches is the analytic method's: 16 points on the receiver, a ray each).
    int samples = kDefaultLinkSamples;
    std::uint64_t seed = 1;
    // Materials whose light is linked as an emitter's besides those that emit in the mesh
    // (rad-ff --emitters): for one that will be made to emit at solve time.
    std::vector<std::string> emitters = {};
    // Shard `shard` of `shards` (rad-ff --rows K/N): only the links of the refinement's tasks
    // this shard owns; merge_link_parts joins all shards into one run's links.
    std::uint32_t shard = 0, shards = 1;
};

struct HierarchyStats {
    std::uint64_t pairs = 0;         // node pairs the oracle examined
    std::uint64_t culled = 0;        // of those, pairs facing away (no rays)
    std::uint64_t rays = 0;          // visibility rays cast
    std::uint64_t leaf_links = 0;    // links between two patches (both directions)
    std::uint64_t outline_pairs = 0; // other node pairs valued by a contour integral
    double tree_seconds = 0, link_seconds = 0;
};

// The tree alone (no links): each surface's patches (connected, on one plane, of one
// material) split at the median of their centroids along the longest side of their box,
// down to single patches, and the surfaces clustered above the same way; deterministic.
radfmt::LinkData build_patch_tree(const radfmt::MeshData& mesh);

// The tree and its links, in parallel (TBB) and byte-identical for any thread count: every
// pair of nodes draws its samples from (seed, pair) alone.
radfmt::LinkData compute_links(const radfmt::MeshData& mesh, const HierarchyOptions& options,
                               HierarchyStats* stats = nullptr);

// The header fields that say how a links file was computed, and for which emitters (the
// materials of `mesh` that emit or are named in options.emitters: their light is linked
// finer).
std::vector<std::pair<std::string, std::string>> link_header_fields(const HierarchyOptions& options,
                                                                    const radfmt::MeshData& mesh);

// The materials that emit in `mesh` (after any overrides) but were not emitters when
// `links_header` was computed: their light travels over links refined as for any surface.
std::vector<std::string> emitters_not_refined_for(const radfmt::Header& links_header,
                                                  const radfmt::MeshData& mesh);

// Shards of a links file (rad-ff --method hierarchical --rows K/N, then --merge): every
// shard K of N exactly once (InputError naming a missing, doubled or foreign part), of one
// mesh, tree and options, joined into what one run would have written to `output`, byte for
// byte. Returns the number of links.
std::uint64_t merge_link_parts(const std::vector<std::string>& paths, const std::string& output);

// Per node of `links`, the area of its patches.
std::vector<double> link_node_areas(const radfmt::MeshData& mesh, const radfmt::LinkData& links);

// A link's factor as it reaches one part of its receiver (radfmt::LinkShares): the part's
// share of the transfer over its share of the node's area (the node's factor where the part
// has no area).
inline double delivered_factor(double factor, std::uint16_t share, double node_area,
                               double part_area) {
    return factor * share * (1.0 / radfmt::kShareTotal) *
           (part_area > 0 ? node_area / part_area : 1.0);
}

// Per patch, its row sum of F through the hierarchy: the factors of the links its leaf and
// every node above it gather over, each as it reaches the patch's part of the node (1 in a
// closed scene).
std::vector<double> link_row_sums(const radfmt::MeshData& mesh, const radfmt::LinkData& links);

} // namespace rad
