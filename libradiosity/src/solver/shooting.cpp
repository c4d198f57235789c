#include "shooting.hpp"

#include <algorithm>
#include <chrono>

namespace rad::solve_impl {

// Progressive refinement (Cohen et al. 1988): shoot the unshot radiosity of the patch with
// the most unshot power. Row i of F holds F_ij; reciprocity gives the shares
// F_ji = F_ij A_i / A_j that the receivers j take.
SolveResult shoot(const TransportOperator& op, const Channels& emission,
                  const SolveControl& control, bool ambient) {
    const auto start = std::chrono::steady_clock::now();
    const auto& ff = *op.form_factors;
    const std::size_t n = op.patch_count();
    const std::size_t channels = emission.channels;
    Channels b = emission;
    Channels unshot = emission;
    double emitted = 0, total_area = 0;
    std::vector<double> mean_reflectance(channels, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        double e = 0;
        for (std::size_t c = 0; c < channels; ++c) e += emission.at(i, c);
        emitted += e * op.area[i];
        total_area += op.area[i];
        for (std::size_t c = 0; c < channels; ++c) mean_reflectance[c] += op.rho(i, c) * op.area[i];
    }
    for (auto& r : mean_reflectance) r = total_area > 0 ? r / total_area : 0;
    // The power of B and of the unshot radiosity per channel, kept up to date shot by shot,
    // so the record of a shot costs O(channels), not a sum over every patch.
    // (Summed by rebuild() below, first at the start.)
    std::vector<double> b_power(channels, 0.0), unshot_total(channels, 0.0);
    // APR's ambient term adds sum_i A_i rho_i x ambient = mean rho x unshot power / (1 - mean
    // rho) per channel.
    auto displayed_power = [&] {
        auto power = b_power;
        if (ambient)
            for (std::size_t c = 0; c < channels; ++c)
                power[c] += mean_reflectance[c] * unshot_total[c] /
                            (1 - std::min(mean_reflectance[c], 0.999999));
        return power;
    };

    auto unshot_fraction = [&](double unshot_power) {
        return emitted > 0 ? unshot_power / emitted : 0;
    };
    // APR's display adds rho_i times Cohen's ambient estimate: the unshot power spread over
    // the scene and multiplied by the interreflection factor 1 / (1 - mean rho).
    auto displayed = [&]() {
        if (!ambient) return b;
        std::vector<double> unshot_mean(channels, 0.0);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t c = 0; c < channels; ++c)
                unshot_mean[c] += unshot.at(i, c) * op.area[i] / total_area;
        Channels shown = b;
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t c = 0; c < channels; ++c)
                shown.at(i, c) +=
                    op.rho(i, c) * unshot_mean[c] / (1 - std::min(mean_reflectance[c], 0.999999));
        return shown;
    };
    auto keep_going = [&](long done, double residual) {
        if (control.max_iterations > 0 && done >= control.max_iterations) return false;
        if (control.tolerance > 0 && done > 0 && residual < control.tolerance) return false;
        return true;
    };

    // The next shooter is the patch with the most unshot power, the lowest index among
    // equals: a max-heap of (power, patch) with stale entries skipped (an entry is current
    // while its power equals the patch's, computed the same way), instead of a scan of every
    // patch per shot. The order of shots is the scan's, exactly.
    auto power_of = [&](std::size_t i) {
        double u = 0;
        for (std::size_t c = 0; c < channels; ++c) u += unshot.at(i, c);
        return u * op.area[i];
    };
    struct Entry {
        double power;
        std::uint32_t patch;
    };
    // "Less" for std::push_heap: lower power, or equal power and a higher index.
    const auto below = [](const Entry& x, const Entry& y) {
        return x.power < y.power || (x.power == y.power && x.patch > y.patch);
    };
    std::vector<Entry> heap;
    double unshot_power = 0;
    auto rebuild = [&] {
        heap.clear();
        unshot_power = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double p = power_of(i);
            unshot_power += p;
            if (p > 0) heap.push_back({p, static_cast<std::uint32_t>(i)});
        }
        std::make_heap(heap.begin(), heap.end(), below);
        // The logged powers too.
        std::fill(b_power.begin(), b_power.end(), 0.0);
        std::fill(unshot_total.begin(), unshot_total.end(), 0.0);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t c = 0; c < channels; ++c) {
                b_power[c] += b.at(i, c) * op.area[i];
                unshot_total[c] += unshot.at(i, c) * op.area[i];
            }
    };
    rebuild();

    std::vector<double> shot(channels);
    long done = 0;
    double residual = 1;
    while (keep_going(done, residual)) {
        // Stale entries pile up (one per reception): start afresh past a few per patch. The
        // running totals are summed afresh then too, so their rounding does not drift.
        if (heap.size() > 4 * n + 64) rebuild();
        while (!heap.empty() && heap.front().power != power_of(heap.front().patch)) {
            std::pop_heap(heap.begin(), heap.end(), below);
            heap.pop_back();
        }
        if (heap.empty()) {
            residual = 0;
            break;
        }
        const std::size_t shooter = heap.front().patch;
        const double best = heap.front().power;
        std::pop_heap(heap.begin(), heap.end(), below);
        heap.pop_back();
        for (std::size_t c = 0; c < channels; ++c) {
            shot[c] = unshot.at(shooter, c);
            unshot.at(shooter, c) = 0;
            unshot_total[c] -= shot[c] * op.area[shooter];
        }
        unshot_power -= best;
        const double a_i = op.area[shooter];
        // (each receiver's new power goes on the heap below, once its channels are all in)
        for (auto k = ff.row_start[shooter]; k < ff.row_start[shooter + 1]; ++k) {
            const auto j = ff.columns[k];
            const double f_ji = ff.values[k] * a_i / op.area[j];
            for (std::size_t c = 0; c < channels; ++c) {
                const double received = op.rho(j, c) * shot[c] * f_ji;
                b.at(j, c) += received;
                unshot.at(j, c) += received;
                unshot_power += received * op.area[j];
                b_power[c] += received * op.area[j];
                unshot_total[c] += received * op.area[j];
            }
            if (const double p = power_of(j); p > 0) {
                heap.push_back({p, j});
                std::push_heap(heap.begin(), heap.end(), below);
            }
        }
        residual = unshot_fraction(std::max(0.0, unshot_power));
        ++done;
        if (control.on_iteration) {
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            control.on_iteration({done, residual, displayed_power(), seconds}, displayed);
        }
    }
    SolveResult result;
    result.radiosity = displayed();
    result.iterations = done;
    result.residual = residual;
    result.converged = control.tolerance > 0 && residual < control.tolerance;
    return result;
}

} // namespace rad::solve_impl
