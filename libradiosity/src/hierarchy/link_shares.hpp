// link_shares: where within a node a link's light arrives or leaves (internal header).
#pragma once
#include "hierarchy/node_geometry.hpp"
#include "radfmt/kinds.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace rad::hierarchy {

// What the rays of a pair saw from one side's points: per sample, where in [0,1) the point
// was drawn along the node's leaf order (the u of NodeGeometries::point), its kernel, and
// whether it saw its partner; and the kernel-weighted share of the pairs that were seen.
struct SideSamples {
    std::span<const double> u;
    std::span<const double> kernel;
    std::span<const std::uint8_t> seen;
    double visible = 1;
};

// Per share slot of `node` (radfmt::share_slots), the share of the pair's transfer with
// `other` that passes through it: each part's form factor to the other node's centroid,
// area over pi r^2 + area (a disc's, so a part beside the other node stays finite), times the
// part's visible fraction of the sample pairs drawn in it (the pair's own where it has none).
// A leaf is one slot of the whole. Deterministic, and the same for either direction of the
// pair, so reciprocity holds part by part.
radfmt::LinkShares link_shares(const radfmt::LinkData& tree, const NodeGeometries& geometry,
                               std::uint32_t node, std::uint32_t other, const SideSamples& samples);

// A leaf's shares: all of it in slot 0.
inline constexpr radfmt::LinkShares kWholeShare = {radfmt::kShareTotal, 0, 0, 0};

} // namespace rad::hierarchy
