#include "shooting.hpp"
#include "shooter_choice.hpp"

#include "radfmt/packed_rows.hpp"
#include "radiosity/error.hpp"

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
    // Unshot power: the channels' unshot radiosity summed, times the area (kChannels: the
    // channel count known to the compiler, or 0).
    template <std::size_t kChannels = 0> double power(const double* s) const {
        const std::size_t channels = kChannels ? kChannels : channels_;
        double u = 0;
        for (std::size_t c = 0; c < channels; ++c) u += unshot(s)[c];
        return u * area(s);
    }
    Channels take(bool unshot_part) const {
        Channels out(n_, channels_);
        for (std::size_t i = 0; i < n_; ++i)
            std::copy_n(unshot_part ? unshot(patch(i)) : b(patch(i)), channels_, out.row(i));
        return out;
    }
    // A patch's state spans two cache lines for RGB (80 bytes): its first and last bytes'
    // lines, without a loop; more channels take the lines between too.
    void prefetch(std::size_t i) const {
        const char* p = reinterpret_cast<const char*>(patch(i));
        const std::size_t bytes = stride_ * sizeof(double);
        __builtin_prefetch(p, 1);
        __builtin_prefetch(p + bytes - 1, 1);
        for (std::size_t offset = 64; offset + 64 < bytes; offset += 64)
            __builtin_prefetch(p + offset, 1);
    }
    std::size_t size() const { return n_; }
    std::size_t channels() const { return channels_; }

  private:
    std::size_t n_, channels_, colours_, stride_;
    std::vector<double> state_;
    std::vector<std::size_t> rho_at_;
};

// Progressive refinement (Cohen et al. 1988): shoot the unshot radiosity of the patch with
// the most unshot power. Row i of F holds F_ij; reciprocity gives the shares
// F_ji = F_ij A_i / A_j that the receivers j take. With `ambient` (APR), what is shown adds
// Cohen's ambient term.
class ProgressiveRefinement {
  public:
    ProgressiveRefinement(const TransportOperator& op, const Channels& emission, bool ambient)
        : op_(op), n_(op.patch_count()), channels_(emission.channels), ambient_(ambient),
          state_(op, emission), mean_reflectance_(channels_, 0.0), b_power_(channels_, 0.0),
          unshot_total_(channels_, 0.0), shot_(channels_), gain_(channels_),
          choice_(n_, &power_of, this) {
        for (std::size_t i = 0; i < n_; ++i) {
            double e = 0;
            for (std::size_t c = 0; c < channels_; ++c) e += emission.at(i, c);
            emitted_ += e * op.area[i];
            total_area_ += op.area[i];
            for (std::size_t c = 0; c < channels_; ++c)
                mean_reflectance_[c] += op.rho(i, c) * op.area[i];
        }
        for (auto& r : mean_reflectance_) r = total_area_ > 0 ? r / total_area_ : 0;
        sum_totals();
    }
    // One shot from the patch with the most unshot power; false when none has any.
    bool shoot_once();
    // The unshot power as a fraction of the emitted.
    double unshot_fraction() const {
        return emitted_ > 0 ? std::max(0.0, unshot_power_) / emitted_ : 0;
    }
    // B (with APR's ambient term), and its power per channel.
    Channels displayed() const;
    std::vector<double> displayed_power() const;

  private:
    // Patch i's unshot power, for the shooter choice's scans.
    static double power_of(const void* self, std::size_t i) {
        const auto& state = static_cast<const ProgressiveRefinement*>(self)->state_;
        return state.power(state.patch(i));
    }
    void sum_totals();
    // The shooter's row received (kChannels: the channel count, 0 when not known here).
    template <std::size_t kChannels, class Columns, class Values>
    void receive(Columns columns, Values values, std::uint64_t size, double a_i);
    // 1 - mean rho of channel c: APR's interreflection factor is its inverse.
    double one_minus_reflectance(std::size_t c) const {
        return 1 - std::min(mean_reflectance_[c], 0.999999);
    }

    const TransportOperator& op_;
    std::size_t n_, channels_;
    bool ambient_;
    ShootingState state_;
    double emitted_ = 0, total_area_ = 0;
    std::vector<double> mean_reflectance_;
    // The power of B and of the unshot radiosity, kept up to date shot by shot, so the record
    // of a shot costs O(channels), not a sum over every patch; summed afresh every n shots
    // (first at the start), so their rounding does not drift.
    double unshot_power_ = 0;
    std::vector<double> b_power_, unshot_total_, shot_, gain_;
    ShooterChoice choice_;
    std::size_t shots_ = 0;
};

void ProgressiveRefinement::sum_totals() {
    unshot_power_ = 0;
    std::fill(b_power_.begin(), b_power_.end(), 0.0);
    std::fill(unshot_total_.begin(), unshot_total_.end(), 0.0);
    for (std::size_t i = 0; i < n_; ++i) {
        const double* s = state_.patch(i);
        unshot_power_ += state_.power(s);
        for (std::size_t c = 0; c < channels_; ++c) {
            b_power_[c] += state_.b(s)[c] * op_.area[i];
            unshot_total_[c] += state_.unshot(s)[c] * op_.area[i];
        }
    }
}

bool ProgressiveRefinement::shoot_once() {
    if (shots_ > 0 && shots_ % std::max<std::size_t>(n_, 1) == 0) sum_totals();
    const std::size_t shooter = choice_.best();
    if (shooter == ShooterChoice::kNone) return false;
    ++shots_;
    const auto& ff = *op_.form_factors;
    double* from = state_.patch(shooter);
    unshot_power_ -= state_.power(from);
    for (std::size_t c = 0; c < channels_; ++c) {
        shot_[c] = state_.unshot(from)[c];
        state_.unshot(from)[c] = 0;
        unshot_total_[c] -= shot_[c] * op_.area[shooter];
    }
    choice_.lower(shooter); // its unshot radiosity is 0 now
    radfmt::with_row_cursors(ff, shooter, [&](auto columns, auto values) {
        if (channels_ == 3)
            receive<3>(columns, values, ff.row_size(shooter), op_.area[shooter]);
        else
            receive<0>(columns, values, ff.row_size(shooter), op_.area[shooter]);
    });
    return true;
}

template <std::size_t kChannels, class Columns, class Values>
void ProgressiveRefinement::receive(Columns columns, Values values, std::uint64_t size,
                                    double a_i) {
    const std::size_t channels = kChannels ? kChannels : channels_;
    // The power received per channel, summed over the row in locals and added to the totals
    // once: accumulating into the members made every reception wait on the previous one.
    double local_gain[kChannels ? kChannels : 1] = {};
    if constexpr (kChannels == 0) std::fill(gain_.begin(), gain_.end(), 0.0);
    double* gain = kChannels ? local_gain : gain_.data();
    double shot[kChannels ? kChannels : 1];
    const double* from = shot_.data();
    if constexpr (kChannels > 0) {
        std::copy_n(shot_.data(), kChannels, shot);
        from = shot;
    }
    // The receivers are known ahead: their state is asked for a few receivers early, so its
    // cache misses overlap instead of stalling each reception in turn.
    Columns ahead = columns;
    radfmt::skip(ahead, std::min<std::uint64_t>(kPrefetchAhead, size));
    for (std::uint64_t k = 0; k < size; ++k) {
        if (k + kPrefetchAhead < size) state_.prefetch(ahead.next());
        const auto j = columns.next();
        double* to = state_.patch(j);
        const double a_j = ShootingState::area(to);
        const double f_ji = values.next() * a_i / a_j;
        for (std::size_t c = 0; c < channels; ++c) {
            const double received = state_.rho(to, c) * from[c] * f_ji;
            state_.b(to)[c] += received;
            state_.unshot(to)[c] += received;
            gain[c] += received * a_j;
        }
        choice_.raise(j, state_.power<kChannels>(to));
    }
    for (std::size_t c = 0; c < channels; ++c) {
        unshot_power_ += gain[c];
        b_power_[c] += gain[c];
        unshot_total_[c] += gain[c];
    }
}

// APR's ambient term adds sum_i A_i rho_i x ambient = mean rho x unshot power x the
// interreflection factor, per channel.
std::vector<double> ProgressiveRefinement::displayed_power() const {
    auto power = b_power_;
    if (ambient_)
        for (std::size_t c = 0; c < channels_; ++c)
            power[c] += mean_reflectance_[c] * unshot_total_[c] / one_minus_reflectance(c);
    return power;
}

// APR's display adds rho_i times Cohen's ambient estimate: the unshot power spread over the
// scene and multiplied by the interreflection factor.
Channels ProgressiveRefinement::displayed() const {
    Channels shown = state_.take(false);
    if (!ambient_) return shown;
    const Channels unshot = state_.take(true);
    std::vector<double> unshot_mean(channels_, 0.0);
    for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t c = 0; c < channels_; ++c)
            unshot_mean[c] += unshot.at(i, c) * op_.area[i] / total_area_;
    for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t c = 0; c < channels_; ++c)
            shown.at(i, c) += op_.rho(i, c) * unshot_mean[c] / one_minus_reflectance(c);
    return shown;
}

} // namespace

SolveResult shoot(const TransportOperator& op, const Channels& emission,
                  const SolveControl& control, bool ambient) {
    // A shot spreads one patch's power along its column of F; links have no columns.
    if (!op.form_factors)
        throw InputError("pr and apr shoot along the rows of a form-factor matrix; a links "
                         "file (rad-ff --method hierarchical) is solved with --method gs or "
                         "jacobi");
    const auto start = std::chrono::steady_clock::now();
    ProgressiveRefinement pr(op, emission, ambient);
    auto keep_going = [&](long done, double residual) {
        if (control.max_iterations > 0 && done >= control.max_iterations) return false;
        if (control.tolerance > 0 && done > 0 && residual < control.tolerance) return false;
        return true;
    };
    long done = 0;
    double residual = 1;
    while (keep_going(done, residual)) {
        if (!pr.shoot_once()) {
            residual = 0;
            break;
        }
        residual = pr.unshot_fraction();
        ++done;
        if (control.on_iteration) {
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            control.on_iteration({done, residual, pr.displayed_power(), seconds},
                                 [&] { return pr.displayed(); });
        }
    }
    SolveResult result;
    result.radiosity = pr.displayed();
    result.iterations = done;
    result.residual = residual;
    result.converged = control.tolerance > 0 && residual < control.tolerance;
    return result;
}

} // namespace rad::solve_impl
