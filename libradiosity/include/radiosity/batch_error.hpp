// The standard error of a sampled figure from independent batches. A point's rays are cast in
// batches, each with its own random turn of the stratified pattern (a Cranley-Patterson
// rotation), so the batches' estimates are independent and identically distributed, each an
// unbiased estimate of the figure. Their sample variance (divided by count - 1) is then an
// unbiased estimate of one batch's variance, and divided by the count, of their mean's. The
// sample variance of single rays would not do: rays of one stratified batch are not
// independent, and it would overstate the error that stratification removes.
#pragma once
#include "radiosity/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rad {

class BatchError {
  public:
    // One batch's estimate (W/m^2 per channel); Welford's update keeps the sums exact enough
    // for thousands of batches of nearly equal values.
    void add(const Rgb& value) {
        ++count_;
        const double n = double(count_);
        for (int c = 0; c < 3; ++c) add_one(mean_[c], m2_[c], value[c], n);
        add_one(luminous_mean_, luminous_m2_, luminous(value), n);
    }
    int count() const { return count_; }
    const Rgb& mean() const { return mean_; }
    // Standard error of the mean per channel, and of its luminous value (NaN under 2 batches).
    Rgb standard_error() const { return {error_of(m2_[0]), error_of(m2_[1]), error_of(m2_[2])}; }
    double luminous_error() const { return error_of(luminous_m2_); }
    double luminous_mean() const { return luminous_mean_; }

  private:
    static void add_one(double& mean, double& m2, double x, double n) {
        const double delta = x - mean;
        mean += delta / n;
        m2 += delta * (x - mean);
    }
    double error_of(double m2) const {
        if (count_ < 2) return std::numeric_limits<double>::quiet_NaN();
        return std::sqrt(std::max(0.0, m2) / (double(count_ - 1) * double(count_)));
    }
    int count_ = 0;
    Rgb mean_{0, 0, 0}, m2_{0, 0, 0};
    double luminous_mean_ = 0, luminous_m2_ = 0;
};

} // namespace rad
