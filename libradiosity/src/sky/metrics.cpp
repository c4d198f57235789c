// Climate-based daylight metrics (IES LM-83-12: sDA, ASE; UDI after Nabil and Mardaljevic
// 2005) and the daylight factor's summary.
#include "radiosity/daylight.hpp"

#include <algorithm>
#include <cmath>

namespace rad {
namespace {
constexpr double kDaylitLux = 300, kSunLux = 1000, kUdiLow = 100, kUdiHigh = 3000;
constexpr double kDaylitShare = 0.5;
constexpr int kSunHours = 250;
} // namespace

AnnualMetrics annual_metrics(const radfmt::AnnualData& year, std::span<const std::uint8_t> inside) {
    AnnualMetrics out;
    const std::size_t n = year.sensors();
    out.sensors.assign(n, SensorMetrics{});
    if (inside.size() == n)
        for (std::size_t k = 0; k < n; ++k) out.sensors[k].valid = !inside[k];
    for (auto o : year.occupied) out.occupied_hours += o;
    if (n == 0 || out.occupied_hours == 0) return out;
    for (std::size_t t = 0; t < year.hours.size(); ++t) {
        if (!year.occupied[t]) continue;
        for (std::size_t k = 0; k < n; ++k) {
            const double lux = year.lux[t * n + k];
            auto& m = out.sensors[k];
            m.da300 += lux >= kDaylitLux;
            m.udi_low += lux < kUdiLow;
            m.udi_useful += lux >= kUdiLow && lux <= kUdiHigh;
            m.udi_high += lux > kUdiHigh;
            m.sun_hours += year.sun_lux[t * n + k] >= kSunLux;
        }
    }
    const double hours = out.occupied_hours;
    for (auto& m : out.sensors) {
        const double scale = m.valid ? 1 / hours : std::nan("");
        m.da300 *= scale;
        m.udi_low *= scale;
        m.udi_useful *= scale;
        m.udi_high *= scale;
    }
    return summarise_sensor_metrics(std::move(out.sensors), out.occupied_hours);
}

AnnualMetrics summarise_sensor_metrics(std::vector<SensorMetrics> sensors, int occupied_hours) {
    AnnualMetrics out;
    out.sensors = std::move(sensors);
    out.occupied_hours = occupied_hours;
    for (const auto& m : out.sensors) {
        if (!m.valid) continue;
        ++out.counted;
        out.sda += m.da300 >= kDaylitShare;
        out.ase += m.sun_hours > kSunHours;
        out.udi_useful += m.udi_useful;
        out.da300 += m.da300;
    }
    if (out.counted == 0) return out;
    const double n = double(out.counted);
    out.sda /= n;
    out.ase /= n;
    out.udi_useful /= n;
    out.da300 /= n;
    return out;
}

DaylightFactorSummary summarise_daylight_factors(std::vector<double> factors) {
    DaylightFactorSummary out;
    const auto with_value =
        std::remove_if(factors.begin(), factors.end(), [](double f) { return std::isnan(f); });
    out.without = static_cast<std::size_t>(factors.end() - with_value);
    factors.erase(with_value, factors.end());
    out.counted = factors.size();
    if (factors.empty()) return out;
    std::sort(factors.begin(), factors.end());
    const std::size_t n = factors.size();
    double sum = 0;
    for (double f : factors) sum += f, out.above2 += f >= 2;
    out.mean = sum / double(n);
    out.median = n % 2 ? factors[n / 2] : 0.5 * (factors[n / 2 - 1] + factors[n / 2]);
    out.min = factors.front();
    out.max = factors.back();
    out.above2 /= double(n);
    return out;
}

namespace {
// The root mean square deviation of replicates from the figure they replicate.
double replicate_error(const std::vector<double>& replicates, double figure) {
    if (replicates.empty()) return std::nan("");
    double sum = 0;
    for (const double r : replicates) sum += (r - figure) * (r - figure);
    return std::sqrt(sum / double(replicates.size()));
}
} // namespace

AnnualErrors annual_errors(const AnnualReplicates& replicates, const AnnualMetrics& metrics,
                           std::size_t first) {
    AnnualErrors out;
    const std::size_t n = metrics.sensors.size(), batches = std::size_t(replicates.batches);
    out.da300.assign(n, std::nan(""));
    out.udi_useful.assign(n, std::nan(""));
    if (batches < 2 || metrics.counted == 0) return out;
    std::vector<double> sda(batches, 0), da_mean(batches, 0), udi_mean(batches, 0);
    std::vector<double> da(batches), udi(batches);
    for (std::size_t k = 0; k < n; ++k) {
        const auto& m = metrics.sensors[k];
        if (!m.valid) continue;
        for (std::size_t b = 0; b < batches; ++b) {
            da[b] = replicates.da300[(first + k) * batches + b];
            udi[b] = replicates.udi_useful[(first + k) * batches + b];
            sda[b] += da[b] >= kDaylitShare;
            da_mean[b] += da[b];
            udi_mean[b] += udi[b];
        }
        out.da300[k] = replicate_error(da, m.da300);
        out.udi_useful[k] = replicate_error(udi, m.udi_useful);
    }
    const double count = double(metrics.counted);
    for (auto* v : {&sda, &da_mean, &udi_mean})
        for (auto& x : *v) x /= count;
    out.sda = replicate_error(sda, metrics.sda);
    out.da300_mean = replicate_error(da_mean, metrics.da300);
    out.udi_useful_mean = replicate_error(udi_mean, metrics.udi_useful);
    return out;
}

} // namespace rad
