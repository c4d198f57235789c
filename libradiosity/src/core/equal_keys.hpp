// Items with equal keys found by sorting hashes (internal header): the duplicates pass (faces
// by their welded corner cycle) and find_twins (patches by their sorted corners).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace rad {

namespace equal_keys_detail {
inline std::uint64_t mix(std::uint64_t h, std::uint64_t x) {
    // splitmix64's finaliser over the running hash and the value.
    h ^= x + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h ^= h >> 30, h *= 0xbf58476d1ce4e5b9ULL, h ^= h >> 27, h *= 0x94d049bb133111ebULL;
    return h ^ (h >> 31);
}
inline std::uint64_t add(std::uint64_t h, std::uint32_t x) {
    return mix(h, x);
}
inline std::uint64_t add(std::uint64_t h, double x) { // -0 as 0: they compare equal
    return mix(h, std::bit_cast<std::uint64_t>(x + 0.0));
}
template <class T, std::size_t N> std::uint64_t add(std::uint64_t h, const std::array<T, N>& a) {
    for (const auto& x : a) h = add(h, x);
    return h;
}
template <class Key> std::uint64_t hash(const Key& key) {
    std::uint64_t h = key.size();
    for (const auto& x : key) h = add(h, x);
    return h;
}
} // namespace equal_keys_detail

// For each of n items, the first (lowest index) item whose key equals its own: itself when
// none before it has that key. key_of(i) returns a sequence of uint32_t, double or arrays of
// them. Items are sorted by a hash of their keys and only equal hashes are compared key by
// key (a std::map keyed by the keys costs a node and an allocation or two per item).
template <class KeyOf> std::vector<std::size_t> first_with_equal_key(std::size_t n, KeyOf key_of) {
    std::vector<std::pair<std::uint64_t, std::size_t>> by_hash(n);
    for (std::size_t i = 0; i < n; ++i) by_hash[i] = {equal_keys_detail::hash(key_of(i)), i};
    std::sort(by_hash.begin(), by_hash.end());
    std::vector<std::size_t> first(n);
    for (std::size_t i = 0; i < n; ++i) first[i] = i;
    for (std::size_t a = 0; a < n;) {
        std::size_t b = a + 1;
        while (b < n && by_hash[b].first == by_hash[a].first) ++b;
        if (b - a > 1) { // the run's items ascend: the first match is the earliest
            std::vector<decltype(key_of(0))> keys;
            for (auto k = a; k < b; ++k) keys.push_back(key_of(by_hash[k].second));
            for (std::size_t x = 1; x < keys.size(); ++x)
                for (std::size_t y = 0; y < x; ++y)
                    if (first[by_hash[a + y].second] == by_hash[a + y].second &&
                        keys[y] == keys[x]) {
                        first[by_hash[a + x].second] = by_hash[a + y].second;
                        break;
                    }
        }
        a = b;
    }
    return first;
}

} // namespace rad
