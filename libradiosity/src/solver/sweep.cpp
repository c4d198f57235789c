#include "sweep.hpp"

#include "radfmt/packed_rows.hpp"

#include <tbb/parallel_for.h>

#include <emmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rad::solve_impl {

namespace {
// The radiosity a row gathers is read from a float copy of B (half the bytes, so that it
// stays in the cache at 1e5 patches and beyond), RGB padded to four lanes; sums are
// accumulated in double. Gauss-Seidel updates the copy with each new value.
struct GatherCopy {
    std::size_t stride;
    std::vector<float> values;
    // Channels [first, first + count) of b; `padded`: RGB in four lanes (gather_rgb's loads).
    GatherCopy(const Channels& b, std::size_t first, std::size_t count, bool padded)
        : stride(padded ? 4 : count), values(b.patches() * stride, 0.0f) {
        for (std::size_t i = 0; i < b.patches(); ++i) set(i, b.row(i) + first, count);
    }
    void set(std::size_t i, const double* row, std::size_t channels) {
        for (std::size_t c = 0; c < channels; ++c)
            values[i * stride + c] = static_cast<float>(row[c]);
    }
};

// sum_k F_ik B_k over a row of `end` entries, RGB: one 4-lane load per entry, two independent
// pairs of double accumulators. `ahead` walks the same columns to prefetch.
template <class Columns, class Values>
inline void gather_rgb(Columns columns, Columns ahead, Values values, std::uint64_t end,
                       const float* from, double* out) {
    __m128d rg0 = _mm_setzero_pd(), bx0 = _mm_setzero_pd();
    __m128d rg1 = _mm_setzero_pd(), bx1 = _mm_setzero_pd();
    // The next entry into one accumulator pair: B's RGB (four float lanes) times F, in double.
    auto add = [&](__m128d& rg, __m128d& bx) {
        const __m128 bj = _mm_loadu_ps(from + 4 * std::size_t(columns.next()));
        const __m128d f = _mm_set1_pd(values.next());
        rg = _mm_add_pd(rg, _mm_mul_pd(f, _mm_cvtps_pd(bj)));
        bx = _mm_add_pd(bx, _mm_mul_pd(f, _mm_cvtps_pd(_mm_movehl_ps(bj, bj))));
    };
    // The columns of a large scene's rows are scattered (each a cache miss): fetch B a few
    // entries ahead, so the misses overlap.
    constexpr std::uint64_t kAhead = 16;
    radfmt::skip(ahead, std::min(kAhead, end));
    std::uint64_t k = 0;
    for (; k + 1 < end; k += 2) {
        if (k + 1 + kAhead < end)
            for (int a = 0; a < 2; ++a)
                _mm_prefetch(reinterpret_cast<const char*>(from + 4 * std::size_t(ahead.next())),
                             _MM_HINT_T0);
        add(rg0, bx0);
        add(rg1, bx1);
    }
    if (k < end) add(rg0, bx0);
    double rg[2], bx[2];
    _mm_storeu_pd(rg, _mm_add_pd(rg0, rg1));
    _mm_storeu_pd(bx, _mm_add_pd(bx0, bx1));
    out[0] = rg[0];
    out[1] = rg[1];
    out[2] = bx[0];
}

// Any channel count (light groups): the same sums, entry by entry.
template <class Columns, class Values>
inline void gather_any(Columns columns, Values values, std::uint64_t end, const float* from,
                       std::size_t channels, double* out) {
    for (std::size_t c = 0; c < channels; ++c) out[c] = 0;
    for (std::uint64_t k = 0; k < end; ++k) {
        const float* bj = from + channels * std::size_t(columns.next());
        const double f = values.next();
        for (std::size_t c = 0; c < channels; ++c) out[c] += f * bj[c];
    }
}

// Row i gathered from `from`, decoding a packed matrix's row as it goes.
template <std::size_t kChannels>
inline void gather_row(const radfmt::FormFactorData& ff, std::size_t i, const float* from,
                       std::size_t channels, double* out) {
    const std::uint64_t end = ff.row_size(i);
    radfmt::with_row_cursors(ff, i, [&](auto columns, auto values) {
        if constexpr (kChannels == 3)
            gather_rgb(columns, columns, values, end, from, out);
        else
            gather_any(columns, values, end, from, channels, out);
    });
}

// One sweep over channels [first, first + count) (kChannels: that count, known to the
// compiler; 0: read at run time).
template <std::size_t kChannels>
std::pair<double, double> sweep_rows(const TransportOperator& op, const Channels& emission,
                                     Channels& b, const Channels& source, std::size_t first,
                                     std::size_t count) {
    const auto& ff = *op.form_factors;
    const std::size_t n = b.patches();
    const std::size_t channels = kChannels ? kChannels : count;
    std::vector<double> gathered(channels);
    GatherCopy copy(source, first, channels, kChannels == 3);
    const bool in_place = &source == &b;
    double change = 0, magnitude = 0;
    for (std::size_t i = 0; i < n; ++i) {
        gather_row<kChannels>(ff, i, copy.values.data(), channels, gathered.data());
        double* bi = b.row(i) + first;
        const double* ei = emission.row(i) + first;
        for (std::size_t c = 0; c < channels; ++c) {
            const double value = ei[c] + op.rho(i, first + c) * gathered[c];
            change += std::abs(value - bi[c]);
            magnitude += std::abs(value);
            bi[c] = value;
        }
        if (in_place) copy.set(i, bi, channels);
    }
    return {change, magnitude};
}

// Many channels (a light group per sky patch: 146 groups, 438 channels): channels are
// independent, so the sweep runs over blocks of kBlockChannels of them in parallel, each over
// every row with its own float copy of its channels. The blocks do not depend on the thread
// count, and their sums are added in block order: the same bytes at any thread count (each
// channel's values are what one sweep over all channels gives).
constexpr std::size_t kBlockChannels = 48;

std::pair<double, double> sweep_blocks(const TransportOperator& op, const Channels& emission,
                                       Channels& b, const Channels& source) {
    const std::size_t blocks = (b.channels + kBlockChannels - 1) / kBlockChannels;
    std::vector<std::pair<double, double>> sums(blocks);
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t k) {
        const std::size_t first = k * kBlockChannels;
        sums[k] = sweep_rows<0>(op, emission, b, source, first,
                                std::min(kBlockChannels, b.channels - first));
    });
    double change = 0, magnitude = 0;
    for (const auto& [c, m] : sums) change += c, magnitude += m;
    return {change, magnitude};
}
} // namespace

std::pair<double, double> sweep(const TransportOperator& op, const Channels& emission, Channels& b,
                                Channels& scratch, bool in_place) {
    if (op.hierarchy) return link_sweep(op, emission, b, in_place);
    if (!in_place) scratch = b;
    const Channels& source = in_place ? b : scratch;
    // RGB, and light groups of 2 to 4 (6 to 12 channels), with the count known to the
    // compiler so the channel loops unroll; any other count reads it at run time.
    switch (b.channels) {
    case 3:
        return sweep_rows<3>(op, emission, b, source, 0, 3);
    case 6:
        return sweep_rows<6>(op, emission, b, source, 0, 6);
    case 9:
        return sweep_rows<9>(op, emission, b, source, 0, 9);
    case 12:
        return sweep_rows<12>(op, emission, b, source, 0, 12);
    default:
        if (b.channels > kBlockChannels) return sweep_blocks(op, emission, b, source);
        return sweep_rows<0>(op, emission, b, source, 0, b.channels);
    }
}

SolveResult solve_by_sweeps(const TransportOperator& op, const Channels& emission,
                            const SolveControl& control, bool in_place) {
    const auto start = std::chrono::steady_clock::now();
    SolveResult result;
    Channels b = emission; // start from B = E
    Channels scratch;
    long done = 0;
    double residual = 1;
    auto keep_going = [&] {
        if (control.max_iterations > 0 && done >= control.max_iterations) return false;
        if (control.tolerance > 0 && done > 0 && residual < control.tolerance) return false;
        return true;
    };
    while (keep_going()) {
        const auto [change, magnitude] = sweep(op, emission, b, scratch, in_place);
        residual = magnitude > 0 ? change / magnitude : 0;
        ++done;
        if (control.on_iteration) {
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            control.on_iteration({done, residual, total_power(op.area, b), seconds},
                                 [&b] { return b; });
        }
        if (magnitude == 0) break; // nothing emits: the black solution is exact
    }
    result.radiosity = std::move(b);
    result.iterations = done;
    result.residual = residual;
    result.converged = control.tolerance > 0 && residual < control.tolerance;
    return result;
}

} // namespace rad::solve_impl
