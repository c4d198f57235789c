// Disjoint sets over 0..n-1 with path halving (internal header): edge classes in
// subdivision, connected surfaces in the orientation checks.
#pragma once
#include <cstddef>
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
};

} // namespace rad
