// EN 17037's daylight factor method: the place's median diffuse illuminance, the levels' daylight
// factors, and the shares of the plane that reach them.
#include "radiosity/en17037.hpp"

#include "radiosity/error.hpp"
#include "radiosity/sky.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

namespace rad {
namespace {
// The shares of the plane: a target over half of it, a minimum over 95%.
constexpr double kTargetShare = 0.5, kMinimumShare = 0.95;
// The illuminance method's share of the daylight hours (F_time).
constexpr double kTimeShare = 0.5;

std::vector<double> diffuse_illuminances(const Weather& weather, std::string& source) {
    std::vector<double> lux;
    const bool given = std::all_of(weather.hours.begin(), weather.hours.end(),
                                   [](const WeatherHour& h) { return h.diffuse_illuminance >= 0; });
    if (given) {
        source = "the weather file's diffuse horizontal illuminance";
        for (const auto& h : weather.hours) lux.push_back(h.diffuse_illuminance);
        return lux;
    }
    source = "the weather file's diffuse radiation by Perez's luminous efficacy";
    const SkyFrame frame;
    for (const auto& h : weather.hours) {
        const auto sun = sun_of_hour(weather, h);
        const bool lit = h.diffuse_horizontal > 0 && sun.zenith < 90;
        lux.push_back(lit ? Sky::perez(h.direct_normal, h.diffuse_horizontal, sun, h.day_of_year(),
                                       h.dew_point, frame, 0.2)
                                .horizontal_illuminance()
                          : 0.0);
    }
    return lux;
}

// The name of the highest level met, in the order minimum, medium, high ("none": not the
// minimum).
template <class Levels> std::string highest_met(const Levels& levels) {
    std::string best = "none";
    for (const auto& level : levels)
        if (level.met) best = level.name;
    return best;
}

double share_at_least(std::span<const double> values, double threshold) {
    std::size_t counted = 0, above = 0;
    for (const double v : values) {
        if (!std::isfinite(v)) continue;
        ++counted;
        above += v >= threshold;
    }
    return counted ? double(above) / double(counted) : 0.0;
}
} // namespace

MedianDiffuse median_external_diffuse_illuminance(const Weather& weather) {
    MedianDiffuse out;
    auto lux = diffuse_illuminances(weather, out.source);
    if (lux.empty()) throw InputError(weather.path + ": no hours to take a median of");
    std::sort(lux.begin(), lux.end(), std::greater<>());
    // The daylight hours: the half of the year with the most light; their median.
    const std::size_t half = lux.size() / 2;
    out.lux = half % 2 ? lux[half / 2] : 0.5 * (lux[half / 2 - 1] + lux[half / 2]);
    return out;
}

std::string En17037Provision::achieved() const {
    return highest_met(levels);
}

En17037Provision en17037_daylight_provision(std::span<const double> factors, double median_lux) {
    if (!(median_lux > 0))
        throw InputError("EN 17037: the median external diffuse illuminance is not positive");
    En17037Provision out;
    out.median_lux = median_lux;
    out.levels = {{{"minimum", 300, 100}, {"medium", 500, 300}, {"high", 750, 500}}};
    for (auto& level : out.levels) {
        level.target_df = 100 * level.target_lux / median_lux;
        level.minimum_df = 100 * level.minimum_lux / median_lux;
        level.target_share = share_at_least(factors, level.target_df);
        level.minimum_share = share_at_least(factors, level.minimum_df);
        level.met = level.target_share >= kTargetShare && level.minimum_share >= kMinimumShare;
    }
    return out;
}

std::vector<std::uint8_t> en17037_daylight_hours(const Weather& weather) {
    std::string source;
    const auto lux = diffuse_illuminances(weather, source);
    std::vector<std::size_t> order(lux.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return lux[a] > lux[b]; });
    std::vector<std::uint8_t> out(lux.size(), 0);
    for (std::size_t k = 0; k < lux.size() / 2; ++k) out[order[k]] = 1;
    return out;
}

std::string En17037Hourly::achieved() const {
    return highest_met(levels);
}

En17037Hourly en17037_illuminance_method(const radfmt::AnnualData& year,
                                         std::span<const std::uint8_t> plane,
                                         const std::vector<std::uint8_t>& daylight_hours) {
    const std::size_t n = year.sensors();
    if (plane.size() != n || daylight_hours.size() != year.hours.size())
        throw InternalError(
            "en17037_illuminance_method: flags not of the year's sensors and hours");
    En17037Hourly out;
    out.levels = {{{"minimum", 300, 100}, {"medium", 500, 300}, {"high", 750, 500}}};
    for (const auto p : plane) out.points += p != 0;
    if (out.points == 0) return out;
    std::array<int, 3> target_hours{}, minimum_hours{};
    for (std::size_t t = 0; t < year.hours.size(); ++t) {
        if (!daylight_hours[t]) continue;
        ++out.daylight_hours;
        for (std::size_t l = 0; l < out.levels.size(); ++l) {
            std::size_t target = 0, minimum = 0;
            for (std::size_t k = 0; k < n; ++k) {
                if (!plane[k]) continue;
                const double lux = year.lux[t * n + k];
                target += lux >= out.levels[l].target_lux;
                minimum += lux >= out.levels[l].minimum_lux;
            }
            target_hours[l] += double(target) >= kTargetShare * double(out.points);
            minimum_hours[l] += double(minimum) >= kMinimumShare * double(out.points);
        }
    }
    for (std::size_t l = 0; l < out.levels.size(); ++l) {
        auto& level = out.levels[l];
        level.target_hours = out.daylight_hours ? double(target_hours[l]) / out.daylight_hours : 0;
        level.minimum_hours =
            out.daylight_hours ? double(minimum_hours[l]) / out.daylight_hours : 0;
        level.met = level.target_hours >= kTimeShare && level.minimum_hours >= kTimeShare;
    }
    return out;
}

} // namespace rad
