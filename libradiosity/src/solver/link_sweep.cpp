// A sweep over a link hierarchy (Hanrahan et al.'s gather with push-pull): pull B up the
// tree (a node's B is its patches' area-weighted mean), gather over each node's links (a
// link reads its source's parts, each by its share, and delivers to its receiver's parts,
// each by its share), push what a node receives down to every patch under it. Gauss-Seidel pulls
// each new patch value into the nodes above it at once, so later gathers see it; Jacobi reads the
// sweep's start.
#include "sweep.hpp"

#include "radiosity/hierarchy.hpp"

#include <cmath>

namespace rad::solve_impl {

namespace {
// Node radiosity, node-major like Channels: every node's area-weighted mean of its patches.
std::vector<double> pull(const LinkTransport& h, const Channels& b) {
    const auto& links = *h.links;
    const std::size_t channels = b.channels;
    std::vector<double> node_b(links.nodes.size() * channels, 0.0);
    for (std::size_t i = links.nodes.size(); i-- > 0;) {
        const auto& n = links.nodes[i];
        double* out = node_b.data() + i * channels;
        if (n.left == radfmt::kNoNode) {
            const double* patch = b.row(links.leaf_order[n.first]);
            for (std::size_t c = 0; c < channels; ++c) out[c] = patch[c];
            continue;
        }
        if (!(h.area[i] > 0)) continue;
        const double wl = h.area[n.left] / h.area[i], wr = h.area[n.right] / h.area[i];
        const double* l = node_b.data() + n.left * channels;
        const double* r = node_b.data() + n.right * channels;
        for (std::size_t c = 0; c < channels; ++c) out[c] = wl * l[c] + wr * r[c];
    }
    return node_b;
}

// What a link sends: its source's parts' radiosity, each weighted by its share.
void link_source(const LinkTransport& h, std::uint64_t l, const std::vector<double>& node_b,
                 std::size_t channels, double* out) {
    const auto& links = *h.links;
    const auto& slots = h.slots[links.source[l]];
    const auto& share = links.source_share[l];
    for (std::size_t c = 0; c < channels; ++c) out[c] = 0;
    for (int k = 0; k < 4; ++k) {
        if (share[k] == 0) continue;
        const double w = share[k] * (1.0 / radfmt::kShareTotal);
        const double* from = node_b.data() + std::size_t(slots[k]) * channels;
        for (std::size_t c = 0; c < channels; ++c) out[c] += w * from[c];
    }
}

// Node i's links: what each delivers, into i itself when it is a patch, else into its parts
// (nodes below i, whose `down` is complete only when they are reached).
void gather_links(const LinkTransport& h, std::size_t i, const std::vector<double>& node_b,
                  std::size_t channels, std::vector<double>& down, std::vector<double>& sent) {
    const auto& links = *h.links;
    const auto& slots = h.slots[i];
    for (auto l = links.link_start[i]; l < links.link_start[i + 1]; ++l) {
        link_source(h, l, node_b, channels, sent.data());
        const double f = links.factor[l];
        const auto& share = links.receiver_share[l];
        for (int k = 0; k < 4; ++k) {
            if (share[k] == 0) continue;
            const double g = delivered_factor(f, share[k], h.area[i], h.area[slots[k]]);
            double* into = down.data() + std::size_t(slots[k]) * channels;
            for (std::size_t c = 0; c < channels; ++c) into[c] += g * sent[c];
        }
    }
}
} // namespace

std::pair<double, double> link_sweep(const TransportOperator& op, const Channels& emission,
                                     Channels& b, bool in_place) {
    const auto& h = *op.hierarchy;
    const auto& links = *h.links;
    const std::size_t channels = b.channels;
    auto node_b = pull(h, b);
    // What each node receives: every node's above it (what a node receives, all its patches
    // do) and what links sent to it as a part of the node they arrive at.
    std::vector<double> down(links.nodes.size() * channels, 0.0);
    std::vector<double> value(channels), sent(channels);
    double change = 0, magnitude = 0;
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        double* g = down.data() + i * channels;
        if (h.parent[i] != radfmt::kNoNode) {
            const double* above = down.data() + std::size_t(h.parent[i]) * channels;
            for (std::size_t c = 0; c < channels; ++c) g[c] += above[c];
        }
        gather_links(h, i, node_b, channels, down, sent);
        const auto& n = links.nodes[i];
        if (n.left != radfmt::kNoNode) continue;
        const std::size_t patch = links.leaf_order[n.first];
        double* bp = b.row(patch);
        const double* ep = emission.row(patch);
        for (std::size_t c = 0; c < channels; ++c) {
            value[c] = ep[c] + op.rho(patch, c) * g[c];
            change += std::abs(value[c] - bp[c]);
            magnitude += std::abs(value[c]);
        }
        if (in_place) {
            // The change, weighted by the patch's share of each node above it.
            for (auto a = h.parent[i]; a != radfmt::kNoNode; a = h.parent[a]) {
                if (!(h.area[a] > 0)) continue;
                const double share = h.area[i] / h.area[a];
                double* above = node_b.data() + std::size_t(a) * channels;
                for (std::size_t c = 0; c < channels; ++c) above[c] += share * (value[c] - bp[c]);
            }
            for (std::size_t c = 0; c < channels; ++c) node_b[i * channels + c] = value[c];
        }
        for (std::size_t c = 0; c < channels; ++c) bp[c] = value[c];
    }
    return {change, magnitude};
}

} // namespace rad::solve_impl
