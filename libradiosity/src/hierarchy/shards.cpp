// merge_link_parts: the shards of a hierarchical refinement (rad-ff --method hierarchical
// --rows K/N) joined into the links file one run would have written, byte for byte.
#include "radfmt/chain.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/hierarchy.hpp"

#include <algorithm>
#include <numeric>

namespace rad {

namespace {
bool part_only(const std::string& key) {
    return key == "shard" || key == "shards" || key == "unsharded_command";
}

struct LinkPart {
    std::string path;
    radfmt::Header header;
    std::uint64_t shard = 0, shards = 0;
};

// Each part's shard K of N; every K of one N exactly once.
void require_every_shard(std::vector<LinkPart>& parts) {
    const auto shards = parts.front().shards;
    std::vector<const LinkPart*> by_shard(shards, nullptr);
    for (const auto& p : parts) {
        if (p.shards != shards)
            throw InputError(p.path + " is shard " + std::to_string(p.shard) + " of " +
                             std::to_string(p.shards) + ", " + parts.front().path + " one of " +
                             std::to_string(shards) + ": give the parts of one --rows K/N split");
        if (p.shard >= shards)
            throw radfmt::FormatError(p.path + ": corrupt header: shard " +
                                      std::to_string(p.shard) + " of " + std::to_string(shards));
        if (by_shard[p.shard])
            throw InputError("shard " + std::to_string(p.shard) + "/" + std::to_string(shards) +
                             " is in two parts: " + by_shard[p.shard]->path + " and " + p.path);
        by_shard[p.shard] = &p;
    }
    for (std::uint64_t k = 0; k < shards; ++k)
        if (!by_shard[k])
            throw InputError("shard " + std::to_string(k) + "/" + std::to_string(shards) +
                             " is in no part (compute it with --rows " + std::to_string(k) + "/" +
                             std::to_string(shards) + ")");
    std::sort(parts.begin(), parts.end(),
              [](const auto& a, const auto& b) { return a.shard < b.shard; });
}

// The same refinement: same tool, mesh, options and command, field for field.
void require_same_refinement(const std::vector<LinkPart>& parts) {
    const auto& first = parts.front();
    for (const auto& p : parts) {
        bool same = p.header.tool == first.header.tool &&
                    p.header.inputs.size() == first.header.inputs.size();
        for (std::size_t i = 0; same && i < p.header.inputs.size(); ++i)
            same = p.header.inputs[i].hash == first.header.inputs[i].hash;
        same = same && p.header.fields.size() == first.header.fields.size();
        for (const auto& [key, value] : first.header.fields)
            if (same && key != "shard" && key != "links") {
                const auto* mine = p.header.find(key);
                same = mine && *mine == value;
            }
        if (!same)
            throw InputError(p.path + " and " + first.path +
                             " are parts of different links files (other mesh or options): "
                             "compute every part with the same mesh and options");
    }
}

struct PartLink {
    std::uint32_t receiver, source;
    float factor;
    radfmt::LinkShares receiver_share, source_share;
};
} // namespace

std::uint64_t merge_link_parts(const std::vector<std::string>& paths, const std::string& output) {
    if (paths.empty()) throw InputError("--merge needs the part files to merge");
    std::vector<LinkPart> parts;
    for (const auto& path : paths) {
        const auto kind = radfmt::Kind::Links;
        LinkPart part{path, radfmt::read_header(path, &kind)};
        if (!part.header.find("shards"))
            throw InputError(path + " is a whole links file, not a part (rad-ff --rows K/N)");
        part.shard = part_row(part.header, "shard", path);
        part.shards = part_row(part.header, "shards", path);
        parts.push_back(std::move(part));
    }
    require_every_shard(parts);
    require_same_refinement(parts);

    radfmt::LinkData merged;
    std::vector<PartLink> all;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        auto part = radfmt::read_links(parts[k].path);
        if (k == 0) {
            merged.patch_count = part.patch_count;
            merged.leaf_order = part.leaf_order;
            merged.nodes = part.nodes;
        } else if (part.patch_count != merged.patch_count || part.leaf_order != merged.leaf_order ||
                   part.nodes != merged.nodes) {
            throw InputError(parts[k].path + " and " + parts[0].path +
                             " hold different trees: compute every part with the same mesh");
        }
        for (std::size_t node = 0; node + 1 < part.link_start.size(); ++node)
            for (auto l = part.link_start[node]; l < part.link_start[node + 1]; ++l)
                all.push_back({static_cast<std::uint32_t>(node), part.source[l], part.factor[l],
                               part.receiver_share[l], part.source_share[l]});
    }
    // One run's order: by receiver, then source (a pair of nodes is linked by one shard only).
    std::sort(all.begin(), all.end(), [](const PartLink& a, const PartLink& b) {
        return a.receiver < b.receiver || (a.receiver == b.receiver && a.source < b.source);
    });
    for (std::size_t l = 1; l < all.size(); ++l)
        if (all[l].receiver == all[l - 1].receiver && all[l].source == all[l - 1].source)
            throw InputError("two parts link node " + std::to_string(all[l].source) + " to node " +
                             std::to_string(all[l].receiver) +
                             ": the parts are not of one --rows K/N split");
    merged.link_start.assign(merged.nodes.size() + 1, 0);
    for (const auto& link : all) {
        ++merged.link_start[link.receiver + 1];
        merged.source.push_back(link.source);
        merged.factor.push_back(link.factor);
        merged.receiver_share.push_back(link.receiver_share);
        merged.source_share.push_back(link.source_share);
    }
    std::partial_sum(merged.link_start.begin(), merged.link_start.end(), merged.link_start.begin());

    auto header = parts.front().header;
    header.version = 0;
    header.command = merged_command(header, parts.front().path, output);
    std::erase_if(header.fields, [](const auto& f) { return part_only(f.first); });
    radfmt::write_links(output, header, merged);
    return merged.links();
}

} // namespace rad
