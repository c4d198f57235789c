// The links kind: a binary tree over the patches and the links between its nodes
// (rad-ff --method hierarchical). Every index is checked on reading, so the solver can
// trust the tree.
#include "kind_table.hpp"

#include "body_checks.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace radfmt {
namespace fs = std::filesystem;

std::array<std::uint32_t, 4> share_slots(const LinkData& links, std::size_t node) {
    std::array<std::uint32_t, 4> slots{kNoNode, kNoNode, kNoNode, kNoNode};
    const auto& n = links.nodes[node];
    if (n.left == kNoNode) {
        slots[0] = static_cast<std::uint32_t>(node);
        return slots;
    }
    for (int side = 0; side < 2; ++side) {
        const auto child = side ? n.right : n.left;
        const auto& c = links.nodes[child];
        if (c.left == kNoNode) {
            slots[2 * side] = child;
        } else {
            slots[2 * side] = c.left;
            slots[2 * side + 1] = c.right;
        }
    }
    return slots;
}

void write_links(const fs::path& path, Header header, const LinkData& links) {
    header.kind = Kind::Links;
    header.set("patches", std::to_string(links.patch_count));
    header.set("nodes", std::to_string(links.nodes.size()));
    header.set("links", std::to_string(links.links()));
    BodyWriter w;
    w.u64(links.patch_count);
    w.array(links.leaf_order);
    w.u64(links.nodes.size());
    w.array(links.nodes);
    w.array(links.link_start);
    w.u64(links.links());
    w.array(links.source);
    w.array(links.factor);
    w.array(links.receiver_share);
    w.array(links.source_share);
    write_file(path, std::move(header), w);
}

namespace {
void check_leaf_order(const LinkData& links, BodyReader& r) {
    std::vector<bool> seen(links.patch_count, false);
    for (const auto patch : links.leaf_order) {
        if (patch >= links.patch_count || seen[patch])
            r.fail("the leaf order is not a permutation of the patches (patch " +
                   std::to_string(patch) + ")");
        seen[patch] = true;
    }
}

// Every node's children come after it, split its patches in two and have no other parent.
void check_tree(const LinkData& links, BodyReader& r) {
    const auto& nodes = links.nodes;
    if (links.patch_count == 0) {
        if (!nodes.empty()) r.fail("a tree without patches");
        return;
    }
    if (nodes.empty() || nodes[0].first != 0 || nodes[0].count != links.patch_count)
        r.fail("the root does not hold every patch");
    std::vector<bool> has_parent(nodes.size(), false);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const auto& n = nodes[i];
        const std::string where = "node " + std::to_string(i);
        if (n.left == kNoNode || n.right == kNoNode) {
            if (n.left != n.right || n.count != 1)
                r.fail(where + " is a leaf of more than a patch");
            continue;
        }
        if (n.left <= i || n.right <= i || n.left >= nodes.size() || n.right >= nodes.size() ||
            has_parent[n.left] || has_parent[n.right])
            r.fail(where + " has children out of order");
        has_parent[n.left] = has_parent[n.right] = true;
        const auto& a = nodes[n.left];
        const auto& b = nodes[n.right];
        if (a.first != n.first || a.count == 0 || b.count == 0 || b.first != n.first + a.count ||
            std::uint64_t(a.count) + b.count != n.count)
            r.fail(where + "'s children do not split its patches");
    }
    for (std::size_t i = 1; i < nodes.size(); ++i)
        if (!has_parent[i]) r.fail("node " + std::to_string(i) + " has no parent");
}

// A node's shares (its slots: share_slots) sum to kShareTotal and leave the slots it does
// not have empty.
void check_shares(const std::array<std::uint32_t, 4>& slots, const LinkShares& shares,
                  BodyReader& r, std::uint64_t link, const char* side) {
    std::uint32_t sum = 0;
    for (int k = 0; k < 4; ++k) {
        if (slots[k] == kNoNode && shares[k] != 0)
            r.fail("link " + std::to_string(link) + " has a " + side +
                   " share for a part its node does not have");
        sum += shares[k];
    }
    if (sum != kShareTotal)
        r.fail("link " + std::to_string(link) + "'s " + side + " shares do not sum to " +
               std::to_string(kShareTotal));
}

void check_links(const LinkData& links, BodyReader& r) {
    const auto& start = links.link_start;
    if (start.size() != links.nodes.size() + 1 || start.front() != 0 ||
        start.back() != links.links())
        r.fail("the link starts do not cover the links");
    for (std::size_t i = 0; i + 1 < start.size(); ++i)
        if (start[i] > start[i + 1]) r.fail("the link starts are not ascending");
    for (std::uint64_t l = 0; l < links.links(); ++l) {
        if (links.source[l] >= links.nodes.size())
            r.fail("link " + std::to_string(l) + " comes from a node that does not exist");
        if (!(links.factor[l] >= 0 && std::isfinite(links.factor[l])))
            r.fail("link " + std::to_string(l) + " has a factor that is negative or not finite");
    }
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        const auto slots = share_slots(links, i);
        const auto& node = links.nodes[i];
        for (auto l = start[i]; l < start[i + 1]; ++l) {
            // A node never gathers from itself or from a part of itself (nor a part from its
            // whole): its patches would light themselves.
            const auto& source = links.nodes[links.source[l]];
            if (source.first < node.first + node.count && node.first < source.first + source.count)
                r.fail("link " + std::to_string(l) + " joins node " + std::to_string(i) +
                       " with node " + std::to_string(links.source[l]) +
                       ", which shares its patches (a patch would light itself)");
            check_shares(slots, links.receiver_share[l], r, l, "receiver");
            check_shares(share_slots(links, links.source[l]), links.source_share[l], r, l,
                         "source");
        }
    }
}
} // namespace

LinkData read_links(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Links;
    BodyReader r(path, &kind);
    LinkData links;
    links.patch_count = r.count(sizeof(std::uint32_t), "patches");
    links.leaf_order = r.array<std::uint32_t>(links.patch_count, "leaf order");
    const auto nodes = r.count(sizeof(LinkNode), "nodes");
    links.nodes = r.array<LinkNode>(nodes, "nodes");
    links.link_start = r.array<std::uint64_t>(nodes + 1, "link starts");
    const auto count =
        r.count(sizeof(std::uint32_t) + sizeof(float) + 2 * sizeof(LinkShares), "links");
    links.source = r.array<std::uint32_t>(count, "link sources");
    links.factor = r.array<float>(count, "link factors");
    links.receiver_share = r.array<LinkShares>(count, "link receiver shares");
    links.source_share = r.array<LinkShares>(count, "link source shares");
    r.expect_end();
    if (links.patch_count >= kNoNode) r.fail("too many patches");
    detail::require_count(r.header(), "patches", links.patch_count, r);
    detail::require_count(r.header(), "nodes", nodes, r);
    detail::require_count(r.header(), "links", count, r);
    check_leaf_order(links, r);
    check_tree(links, r);
    check_links(links, r);
    if (header_out) *header_out = r.take_header();
    return links;
}

namespace detail {
void links_csv(const fs::path& path, std::ostream& out) {
    const auto links = read_links(path);
    out << "node,first,count,source,f,r0,r1,r2,r3,s0,s1,s2,s3\n";
    char line[240];
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        const auto& n = links.nodes[i];
        for (auto l = links.link_start[i]; l < links.link_start[i + 1]; ++l) {
            const auto& r = links.receiver_share[l];
            const auto& s = links.source_share[l];
            std::snprintf(line, sizeof line, "%zu,%u,%u,%u,%.9g,%u,%u,%u,%u,%u,%u,%u,%u\n", i,
                          n.first, n.count, links.source[l], double(links.factor[l]), r[0], r[1],
                          r[2], r[3], s[0], s[1], s[2], s[3]);
            out << line;
        }
        if (!out) return;
    }
}

std::string links_summary(const fs::path& path, Header& header) {
    const auto links = read_links(path, &header);
    char text[200];
    std::snprintf(text, sizeof text, "%llu patches, %zu nodes, %llu links (%.2f a patch)",
                  static_cast<unsigned long long>(links.patch_count), links.nodes.size(),
                  static_cast<unsigned long long>(links.links()),
                  links.patch_count ? double(links.links()) / double(links.patch_count) : 0.0);
    return text;
}
} // namespace detail

} // namespace radfmt
