// The random streams of the chain: one per (seed, stream), so results never depend on which
// thread computes what.
#pragma once
#include <cstdint>

namespace rad {

// splitmix64: tiny, fast and good enough for sample placement; seeded per row or point.
struct Rng {
    std::uint64_t state;
    Rng(std::uint64_t seed, std::uint64_t stream)
        : state(seed * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull)) {
        next();
    }
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }
};

// The stream of batch `batch` of point `index`: independent of every other batch's and point's
// (the batches of an error bar, batch_error.hpp).
inline Rng batch_stream(std::uint64_t seed, std::uint64_t index, int batch) {
    Rng mixer(seed, static_cast<std::uint64_t>(batch));
    return Rng(mixer.next(), index);
}

} // namespace rad
