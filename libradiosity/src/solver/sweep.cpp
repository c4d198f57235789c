#include "sweep.hpp"

#include <chrono>
#include <cmath>

namespace rad::solve_impl {

namespace {
// kChannels > 0 fixes the channel count at compile time (the common RGB case); 0 reads it
// from the data. The arithmetic and its order are the same either way.
template <std::size_t kChannels>
std::pair<double, double> sweep_rows(const TransportOperator& op, const Channels& emission,
                                     Channels& b, const Channels& source) {
    const auto& ff = *op.form_factors;
    const std::size_t n = b.patches();
    const std::size_t channels = kChannels ? kChannels : b.channels;
    std::vector<double> dynamic(kChannels ? 0 : channels);
    double fixed[kChannels ? kChannels : 1];
    double* gathered = kChannels ? fixed : dynamic.data();
    double change = 0, magnitude = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t c = 0; c < channels; ++c) gathered[c] = 0;
        for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k) {
            const double* bj = source.row(ff.columns[k]);
            const double f = ff.values[k];
            for (std::size_t c = 0; c < channels; ++c) gathered[c] += f * bj[c];
        }
        double* bi = b.row(i);
        const double* ei = emission.row(i);
        for (std::size_t c = 0; c < channels; ++c) {
            const double value = ei[c] + op.rho(i, c) * gathered[c];
            change += std::abs(value - bi[c]);
            magnitude += std::abs(value);
            bi[c] = value;
        }
    }
    return {change, magnitude};
}
} // namespace

std::pair<double, double> sweep(const TransportOperator& op, const Channels& emission, Channels& b,
                                Channels& scratch, bool in_place) {
    if (!in_place) scratch = b;
    const Channels& source = in_place ? b : scratch;
    // RGB, and light groups of 2 to 4 (6 to 12 channels), with the count known to the
    // compiler so the channel loops unroll; any other count reads it at run time.
    switch (b.channels) {
    case 3:
        return sweep_rows<3>(op, emission, b, source);
    case 6:
        return sweep_rows<6>(op, emission, b, source);
    case 9:
        return sweep_rows<9>(op, emission, b, source);
    case 12:
        return sweep_rows<12>(op, emission, b, source);
    default:
        return sweep_rows<0>(op, emission, b, source);
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
            control.on_iteration({done, residual, total_power(op.area, b), seconds}, b);
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
