// direct_light: how unevenly the emitters light each node of the patch tree, so that the link
// oracle can refine where a source's radiosity varies (internal header).
#pragma once
#include "hierarchy/node_geometry.hpp"
#include "radiosity/rays.hpp"

#include <cstdint>
#include <vector>

namespace rad::hierarchy {

// Per node, the direct irradiance of its patches from the emitters, each emitter at an
// exitance of 1 (links are refined for light groups mixed after the solve, so no emitter's
// setting is known): its area-weighted mean, and its standard deviation within the node's
// share slots (radfmt::share_slots; a link reads each slot's mean radiosity, so only the
// variation inside them goes unseen). `reference` is the mean over all patches.
struct DirectLight {
    std::vector<float> mean, spread;
    double reference = 0;
    bool empty() const { return mean.empty(); }
};

// Each patch's irradiance at its centroid from kLightPoints points spread over the emitters'
// area (each a disc of its share of that area), traced for occlusion. Empty when no patch
// is an emitter. Deterministic for (mesh, tree, seed), in parallel.
DirectLight estimate_direct_light(const radfmt::MeshData& mesh, const radfmt::LinkData& tree,
                                  const NodeGeometries& geometry, const RayScene& scene,
                                  std::uint64_t seed);

inline constexpr int kLightPoints = 64;

} // namespace rad::hierarchy
