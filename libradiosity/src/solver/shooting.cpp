#include "shooting.hpp"
#include "shooter_choice.hpp"

#include <algorithm>
#include <chrono>

namespace rad::solve_impl {

namespace {

constexpr std::size_t kPrefetchAhead = 32;

// What a shot reads and writes of each receiver, side by side (area, reflectances, unshot
// and B per channel): one or two cache lines a receiver instead of one per array.
class ShootingState {
  public:
    ShootingState(const TransportOperator& op, const Channels& emission)
        : n_(op.patch_count()), channels_(emission.channels), colours_(op.colours),
          stride_(1 + colours_ + 2 * channels_), state_(n_ * stride_), rho_at_(channels_) {
        // Where channel c's reflectance sits (light groups repeat the colours), looked up
        // rather than computed: a modulo per receiver and channel cost more than the rest.
        for (std::size_t c = 0; c < channels_; ++c) rho_at_[c] = 1 + c % colours_;
        for (std::size_t i = 0; i < n_; ++i) {
            double* s = state_.data() + i * stride_;
            s[0] = op.area[i];
            for (std::size_t c = 0; c < colours_; ++c) s[1 + c] = op.rho(i, c);
            for (std::size_t c = 0; c < channels_; ++c) unshot(s)[c] = b(s)[c] = emission.at(i, c);
        }
    }
    double* patch(std::size_t i) { return state_.data() + i * stride_; }
    const double* patch(std::size_t i) const { return state_.data() + i * stride_; }
    static double area(const double* s) { return s[0]; }
    double rho(const double* s, std::size_t c) const { return s[rho_at_[c]]; }
    double* unshot(double* s) const { return s + 1 + colours_; }
    const double* unshot(const double* s) const { return s + 1 + colours_; }
    double* b(double* s) const { return s + 1 + colours_ + channels_; }
    const double* b(const double* s) const { return s + 1 + colours_ + channels_; }
    // Unshot power: the channels' unshot radiosity summed, times the area.
    double power(const double* s) const {
        double u = 0;
        for (std::size_t c = 0; c < channels_; ++c) u += unshot(s)[c];
        return u * area(s);
    }
    Channels take(bool unshot_part) const {
        Channels out(n_, channels_);
        for (std::size_t i = 0; i < n_; ++i)
            std::copy_n(unshot_part ? unshot(patch(i)) : b(patch(i)), channels_, out.row(i));
        return out;
    }
    void prefetch(std::size_t i) const {
        const char* p = reinterpret_cast<const char*>(patch(i));
        for (std::size_t offset = 0; offset < stride_ * sizeof(double); offset += 64)
            __builtin_prefetch(p + offset, 1);
    }
    std::size_t size() const { return n_; }
    std::size_t channels() const { return channels_; }

  private:
    std::size_t n_, channels_, colours_, stride_;
    std::vector<double> state_;
    std::vector<std::size_t> rho_at_;
};

} // namespace

// Progressive refinement (Cohen et al. 1988): shoot the unshot radiosity of the patch with
// the most unshot power. Row i of F holds F_ij; reciprocity gives the shares
// F_ji = F_ij A_i / A_j that the receivers j take.
SolveResult shoot(const TransportOperator& op, const Channels& emission,
                  const SolveControl& control, bool ambient) {
    const auto start = std::chrono::steady_clock::now();
    const auto& ff = *op.form_factors;
    const std::size_t n = op.patch_count();
    const std::size_t channels = emission.channels;
    ShootingState state(op, emission);
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
    // so the record of a shot costs O(channels), not a sum over every patch; summed afresh
    // every n shots (first at the start), so their rounding does not drift.
    std::vector<double> b_power(channels, 0.0), unshot_total(channels, 0.0);
    double unshot_power = 0;
    auto sum_totals = [&] {
        unshot_power = 0;
        std::fill(b_power.begin(), b_power.end(), 0.0);
        std::fill(unshot_total.begin(), unshot_total.end(), 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            const double* s = state.patch(i);
            unshot_power += state.power(s);
            for (std::size_t c = 0; c < channels; ++c) {
                b_power[c] += state.b(s)[c] * op.area[i];
                unshot_total[c] += state.unshot(s)[c] * op.area[i];
            }
        }
    };
    sum_totals();
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
    auto unshot_fraction = [&](double power) { return emitted > 0 ? power / emitted : 0; };
    // APR's display adds rho_i times Cohen's ambient estimate: the unshot power spread over
    // the scene and multiplied by the interreflection factor 1 / (1 - mean rho).
    auto displayed = [&]() {
        Channels shown = state.take(false);
        if (!ambient) return shown;
        const Channels unshot = state.take(true);
        std::vector<double> unshot_mean(channels, 0.0);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t c = 0; c < channels; ++c)
                unshot_mean[c] += unshot.at(i, c) * op.area[i] / total_area;
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

    std::vector<double> powers(n);
    for (std::size_t i = 0; i < n; ++i) powers[i] = state.power(state.patch(i));
    ShooterChoice choice(std::move(powers));
    std::vector<double> shot(channels);
    long done = 0;
    double residual = 1;
    while (keep_going(done, residual)) {
        if (done > 0 && done % static_cast<long>(std::max<std::size_t>(n, 1)) == 0) sum_totals();
        const std::size_t shooter = choice.best();
        if (shooter == ShooterChoice::kNone) {
            residual = 0;
            break;
        }
        double* from = state.patch(shooter);
        unshot_power -= state.power(from);
        for (std::size_t c = 0; c < channels; ++c) {
            shot[c] = state.unshot(from)[c];
            state.unshot(from)[c] = 0;
            unshot_total[c] -= shot[c] * op.area[shooter];
        }
        choice.lower(shooter, 0);
        const double a_i = op.area[shooter];
        const auto row_end = ff.row_start[shooter + 1];
        for (auto k = ff.row_start[shooter]; k < row_end; ++k) {
            // The receivers are known ahead: their state is asked for a few receivers early,
            // so its cache misses overlap instead of stalling each reception in turn.
            if (k + kPrefetchAhead < row_end) state.prefetch(ff.columns[k + kPrefetchAhead]);
            const auto j = ff.columns[k];
            double* to = state.patch(j);
            const double a_j = ShootingState::area(to);
            const double f_ji = ff.values[k] * a_i / a_j;
            for (std::size_t c = 0; c < channels; ++c) {
                const double received = state.rho(to, c) * shot[c] * f_ji;
                state.b(to)[c] += received;
                state.unshot(to)[c] += received;
                unshot_power += received * a_j;
                b_power[c] += received * a_j;
                unshot_total[c] += received * a_j;
            }
            choice.raise(j, state.power(to));
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
