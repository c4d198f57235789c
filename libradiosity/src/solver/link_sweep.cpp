// A sweep over a link hierarchy (Hanrahan et al.'s gather with push-pull): pull B up the
// tree (a node's B is its patches' area-weighted mean), gather over each node's links, push
// what a node gathers down to every patch under it. Gauss-Seidel pulls each new patch value
// into the nodes above it at once, so later gathers see it; Jacobi reads the sweep's start.
#include "sweep.hpp"

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
} // namespace

std::pair<double, double> link_sweep(const TransportOperator& op, const Channels& emission,
                                     Channels& b, bool in_place) {
    const auto& h = *op.hierarchy;
    const auto& links = *h.links;
    const std::size_t channels = b.channels;
    auto node_b = pull(h, b);
    // What each node has gathered, its own links and every node's above it.
    std::vector<double> down(links.nodes.size() * channels, 0.0);
    std::vector<double> value(channels);
    double change = 0, magnitude = 0;
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        double* g = down.data() + i * channels;
        if (h.parent[i] != radfmt::kNoNode) {
            const double* above = down.data() + std::size_t(h.parent[i]) * channels;
            for (std::size_t c = 0; c < channels; ++c) g[c] = above[c];
        }
        for (auto l = links.link_start[i]; l < links.link_start[i + 1]; ++l) {
            const double f = links.factor[l];
            const double* from = node_b.data() + std::size_t(links.source[l]) * channels;
            for (std::size_t c = 0; c < channels; ++c) g[c] += f * from[c];
        }
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
