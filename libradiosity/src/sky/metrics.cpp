// Climate-based daylight metrics (IES LM-83-12: sDA, ASE; UDI after Nabil and Mardaljevic
// 2005) and the daylight factor's summary.
#include "radiosity/daylight.hpp"

#include <algorithm>

namespace rad {
namespace {
constexpr double kDaylitLux = 300, kSunLux = 1000, kUdiLow = 100, kUdiHigh = 3000;
constexpr double kDaylitShare = 0.5;
constexpr int kSunHours = 250;
} // namespace

AnnualMetrics annual_metrics(const radfmt::AnnualData& year) {
    AnnualMetrics out;
    const std::size_t n = year.sensors();
    out.sensors.assign(n, SensorMetrics{});
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
        m.da300 /= hours;
        m.udi_low /= hours;
        m.udi_useful /= hours;
        m.udi_high /= hours;
    }
    return summarise_sensor_metrics(std::move(out.sensors), out.occupied_hours);
}

AnnualMetrics summarise_sensor_metrics(std::vector<SensorMetrics> sensors, int occupied_hours) {
    AnnualMetrics out;
    out.sensors = std::move(sensors);
    out.occupied_hours = occupied_hours;
    if (out.sensors.empty()) return out;
    for (const auto& m : out.sensors) {
        out.sda += m.da300 >= kDaylitShare;
        out.ase += m.sun_hours > kSunHours;
        out.udi_useful += m.udi_useful;
        out.da300 += m.da300;
    }
    const double n = double(out.sensors.size());
    out.sda /= n;
    out.ase /= n;
    out.udi_useful /= n;
    out.da300 /= n;
    return out;
}

DaylightFactorSummary summarise_daylight_factors(std::vector<double> factors) {
    DaylightFactorSummary out;
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

} // namespace rad
