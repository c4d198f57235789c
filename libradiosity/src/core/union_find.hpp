// Disjoint sets over 0..n-1 with path halving (internal header): edge classes in
// subdivision, connected surfaces in the orientation checks, pieces that touch.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <vector>

namespace rad {

struct UnionFind {
    std::vector<std::size_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    std::size_t find(std::size_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
    // The sets' members, each ascending, the sets in the order of their first member.
    std::vector<std::vector<std::size_t>> groups() {
        std::map<std::size_t, std::size_t> index_of_root;
        std::vector<std::vector<std::size_t>> out;
        for (std::size_t k = 0; k < parent.size(); ++k) {
            const auto [it, added] = index_of_root.try_emplace(find(k), out.size());
            if (added) out.emplace_back();
            out[it->second].push_back(k);
        }
        return out;
    }
};

// Items 0..count-1 joined where they share a key (a corner welded by position, say), as
// groups(): `keys_of(k, add)` calls add(key) for each key of item k.
template <class KeysOf>
std::vector<std::vector<std::size_t>> groups_sharing_keys(std::size_t count, KeysOf&& keys_of) {
    UnionFind sets(count);
    std::map<std::uint64_t, std::size_t> first_with; // a key: the first item that has it
    for (std::size_t k = 0; k < count; ++k)
        keys_of(k, [&](std::uint64_t key) {
            const auto [it, added] = first_with.try_emplace(key, k);
            if (!added) sets.unite(k, it->second);
        });
    return sets.groups();
}

} // namespace rad
