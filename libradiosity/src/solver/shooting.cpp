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

    std::vector<double> shot(channels);
    long done = 0;
    double residual = 1;
    while (keep_going(done, residual)) {
        std::size_t shooter = 0;
        double best = -1, unshot_power = 0;
        for (std::size_t i = 0; i < n; ++i) {
            double u = 0;
            for (std::size_t c = 0; c < channels; ++c) u += unshot.at(i, c);
            const double power = u * op.area[i];
            unshot_power += power;
            if (power > best) {
                best = power;
                shooter = i;
            }
        }
        if (best <= 0) {
            residual = 0;
            break;
        }
        for (std::size_t c = 0; c < channels; ++c) {
            shot[c] = unshot.at(shooter, c);
            unshot.at(shooter, c) = 0;
        }
        unshot_power -= best;
        const double a_i = op.area[shooter];
        for (auto k = ff.row_start[shooter]; k < ff.row_start[shooter + 1]; ++k) {
            const auto j = ff.columns[k];
            const double f_ji = ff.values[k] * a_i / op.area[j];
            for (std::size_t c = 0; c < channels; ++c) {
                const double received = op.rho(j, c) * shot[c] * f_ji;
                b.at(j, c) += received;
                unshot.at(j, c) += received;
                unshot_power += received * op.area[j];
            }
        }
        residual = unshot_fraction(std::max(0.0, unshot_power));
        ++done;
        if (control.on_iteration) {
            const auto shown = displayed();
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            control.on_iteration({done, residual, total_power(op.area, shown), seconds}, shown);
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
