#include "hierarchy/link_shares.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad::hierarchy {

namespace {
constexpr double kPi = std::numbers::pi;

// The form factor from part `part` to the centroid of `other`, as from a disc of the part's
// area facing it (a cosine of 1 at a side that is not flat).
double part_factor(const NodeGeometry& part, const NodeGeometry& other) {
    const Vec3 d = other.centroid - part.centroid;
    const double r2 = dot(d, d);
    if (!(r2 > 0)) return part.area;
    const double r = std::sqrt(r2);
    const double from = part.planar ? dot(part.normal, d) / r : 1.0;
    const double to = other.planar ? -dot(other.normal, d) / r : 1.0;
    if (from <= 0 || to <= 0) return 0.0;
    return part.area * from * to / (kPi * r2 + part.area);
}

// Per slot, the kernel-weighted share of the sample pairs drawn in it that were seen (-1
// where none of its pairs face).
std::array<double, 4> slot_visibility(const std::array<double, 4>& slot_end,
                                      const SideSamples& samples) {
    std::array<double, 4> seen{}, facing{};
    for (std::size_t k = 0; k < samples.u.size(); ++k) {
        if (!(samples.kernel[k] > 0)) continue;
        int slot = 0;
        while (slot < 3 && samples.u[k] >= slot_end[slot]) ++slot;
        facing[slot] += samples.kernel[k];
        if (samples.seen[k]) seen[slot] += samples.kernel[k];
    }
    std::array<double, 4> out;
    for (int s = 0; s < 4; ++s) out[s] = facing[s] > 0 ? seen[s] / facing[s] : -1.0;
    return out;
}

// Weights in 65535ths that sum to kShareTotal (the largest takes the rounding); all the
// weight on the present slots by area when the weights are all zero.
radfmt::LinkShares quantized(std::array<double, 4> weight,
                             const std::array<std::uint32_t, 4>& slots,
                             const NodeGeometries& geometry) {
    double total = 0;
    for (const double w : weight) total += w;
    if (!(total > 0)) {
        for (int s = 0; s < 4; ++s)
            weight[s] = slots[s] != radfmt::kNoNode ? geometry[slots[s]].area : 0;
        total = 0;
        for (const double w : weight) total += w;
        if (!(total > 0)) return kWholeShare; // parts of no area: slot 0 takes it
    }
    radfmt::LinkShares out{};
    std::uint32_t sum = 0;
    int largest = 0;
    for (int s = 0; s < 4; ++s) {
        out[s] = static_cast<std::uint16_t>(std::lround(weight[s] / total * radfmt::kShareTotal));
        sum += out[s];
        if (weight[s] > weight[largest]) largest = s;
    }
    out[largest] =
        static_cast<std::uint16_t>(int(out[largest]) + int(radfmt::kShareTotal) - int(sum));
    return out;
}
} // namespace

radfmt::LinkShares link_shares(const radfmt::LinkData& tree, const NodeGeometries& geometry,
                               std::uint32_t node, std::uint32_t other,
                               const SideSamples& samples) {
    if (tree.is_leaf(node)) return kWholeShare;
    const auto slots = radfmt::share_slots(tree, node);
    // Where each slot ends along the node's leaf order, as a fraction of its area.
    std::array<double, 4> slot_end{};
    double before = 0;
    for (int s = 0; s < 4; ++s) {
        if (slots[s] != radfmt::kNoNode) before += geometry[slots[s]].area;
        slot_end[s] = before / geometry[node].area;
    }
    const auto visible = slot_visibility(slot_end, samples);
    std::array<double, 4> weight{};
    for (int s = 0; s < 4; ++s) {
        if (slots[s] == radfmt::kNoNode) continue;
        weight[s] = part_factor(geometry[slots[s]], geometry[other]) *
                    (visible[s] >= 0 ? visible[s] : samples.visible);
    }
    return quantized(weight, slots, geometry);
}

} // namespace rad::hierarchy
