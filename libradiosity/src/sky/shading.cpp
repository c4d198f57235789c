// Operable shading over a year (shading.hpp): which hours a window's shaded state is used, by
// IES LM-83-12's rule or the user's, and the year as operated.
#include "radiosity/shading.hpp"

#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rad {
namespace {
// LM-83-12's operable shading: down when more than 2% of the sensors get 1000 lx or more of
// direct sun (the comparisons as Honeybee's LEED post-processing makes them: >= 1000 lx, > 2%).
constexpr double kLm83Lux = 1000, kLm83Share = 0.02;

double rule_number(std::string_view text, std::string_view field, std::string_view whole) {
    double value = 0;
    if (!parse_number(text, value) || !std::isfinite(value) || value < 0)
        throw InputError("shading rule '" + std::string(whole) + "': " + std::string(field) + " '" +
                         std::string(text) + "' is not a number of 0 or more");
    return value;
}

ShadingRule sun_rule(std::string_view text) {
    // sun:LUX:PERCENT
    const auto rest = text.substr(4);
    const auto colon = rest.find(':');
    if (colon == std::string_view::npos)
        throw InputError("shading rule '" + std::string(text) +
                         "': give sun:LUX:PERCENT (the blinds go down when more than PERCENT % "
                         "of the sensors get LUX or more of direct sun; LM-83: sun:1000:2)");
    ShadingRule rule;
    rule.lux = rule_number(rest.substr(0, colon), "LUX", text);
    const double percent = rule_number(rest.substr(colon + 1), "PERCENT", text);
    if (percent >= 100)
        throw InputError("shading rule '" + std::string(text) +
                         "': PERCENT must be under 100 (more than 100% of the sensors never get "
                         "sun, so the blinds would never go down)");
    rule.share = percent / 100;
    return rule;
}
} // namespace

std::string ShadingRule::describe() const {
    if (kind == Kind::schedule) return "the schedule " + text.substr(9);
    char out[200];
    std::snprintf(out, sizeof out,
                  "%s (blinds down when more than %g%% of the sensors get %g lx or more of "
                  "direct sun)",
                  lux == kLm83Lux && share == kLm83Share ? "LM-83's rule" : "the sun rule",
                  100 * share, lux);
    return out;
}

ShadingRule parse_shading_rule(std::string_view text, std::size_t hours) {
    ShadingRule rule;
    if (text == "lm83") {
        rule.lux = kLm83Lux;
        rule.share = kLm83Share;
    } else if (text.starts_with("sun:")) {
        rule = sun_rule(text);
    } else if (text.starts_with("schedule:") && text.size() > 9) {
        rule.kind = ShadingRule::Kind::schedule;
        rule.schedule = read_hourly_flags(std::string(text.substr(9)), hours, "shading schedule");
    } else {
        throw InputError("shading rule '" + std::string(text) +
                         "': give lm83 (IES LM-83-12), sun:LUX:PERCENT or schedule:FILE");
    }
    rule.text = text;
    return rule;
}

std::vector<double> sunlit_shares(const radfmt::AnnualData& open,
                                  std::span<const std::uint8_t> judged, double lux) {
    const std::size_t n = std::min(open.sensors(), judged.size()), hours = open.hours.size();
    const auto count = std::count_if(judged.begin(), judged.begin() + long(n),
                                     [](std::uint8_t j) { return j != 0; });
    std::vector<double> out(hours, 0.0);
    if (count == 0) return out;
    for (std::size_t t = 0; t < hours; ++t) {
        std::size_t sunlit = 0;
        for (std::size_t k = 0; k < n; ++k)
            sunlit += judged[k] && open.sun_lux[t * open.sensors() + k] >= lux;
        out[t] = double(sunlit) / double(count);
    }
    return out;
}

std::vector<std::uint8_t> shaded_hours(const ShadingRule& rule, const std::vector<double>& shares) {
    if (rule.kind == ShadingRule::Kind::schedule) return rule.schedule;
    std::vector<std::uint8_t> out(shares.size());
    for (std::size_t t = 0; t < shares.size(); ++t) out[t] = shares[t] > rule.share;
    return out;
}

std::vector<std::uint8_t> shaded_hours(const ShadingRule& rule, const radfmt::AnnualData& open,
                                       std::span<const std::uint8_t> judged) {
    if (rule.kind == ShadingRule::Kind::schedule) return rule.schedule;
    return shaded_hours(rule, sunlit_shares(open, judged, rule.lux));
}

radfmt::AnnualData operated_year(const radfmt::AnnualData& open, const radfmt::AnnualData& closed,
                                 const std::vector<std::uint8_t>& shaded) {
    const std::size_t n = open.sensors(), hours = open.hours.size();
    if (closed.sensors() != n || closed.hours != open.hours || shaded.size() != hours)
        throw InternalError("operated_year: the states' years differ in sensors or hours");
    radfmt::AnnualData out = open;
    for (std::size_t t = 0; t < hours; ++t)
        if (shaded[t])
            std::copy_n(closed.lux.begin() + long(t * n), n, out.lux.begin() + long(t * n));
    return out;
}

namespace {
// The occupied hours with the shaded state (`want_down`) or the open one.
std::vector<std::uint8_t> hours_where(const std::vector<std::uint8_t>& occupied,
                                      const std::vector<std::uint8_t>& down, bool want_down) {
    std::vector<std::uint8_t> out(occupied.size());
    for (std::size_t t = 0; t < occupied.size(); ++t)
        out[t] = occupied[t] && (down[t] != 0) == want_down;
    return out;
}
} // namespace

OperatedYear operated_annual(const DaylightSensors& open, const DaylightSensors& closed,
                             const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                             const Weather& weather, const std::vector<std::uint8_t>& occupied,
                             double ground, const ShadingRule& rule,
                             std::span<const std::uint8_t> judged,
                             std::span<const std::uint8_t> inside, bool quiet,
                             std::vector<std::string>* notes, AnnualReplicates* replicates) {
    // The year's skies, made once: the closed state shares them when its solution has the
    // open one's sky patches and compass (a window's states: the same .sky subdivision).
    const auto open_skies = hourly_skies(weather, open.patches(), open.frame(), ground);
    const bool shared = closed.patches().count() == open.patches().count() &&
                        closed.frame().north_deg == open.frame().north_deg;
    const auto own_skies =
        shared ? HourlySkies{} : hourly_skies(weather, closed.patches(), closed.frame(), ground);
    const auto& closed_skies = shared ? open_skies : own_skies;
    const auto open_year =
        annual_illuminance(open, open_skies, positions, normals, weather, occupied, quiet, notes);
    const auto closed_year = annual_illuminance(closed, closed_skies, positions, normals, weather,
                                                occupied, quiet, nullptr);
    OperatedYear out;
    out.rule = rule.describe();
    out.sunlit = sunlit_shares(open_year, judged, rule.lux);
    out.down = shaded_hours(rule, out.sunlit);
    out.year = operated_year(open_year, closed_year, out.down);
    const int occupied_hours = int(std::count(occupied.begin(), occupied.end(), 1));
    if (replicates)
        for (const auto* sensors : {&open, &closed})
            add_annual_replicates(*sensors, sensors == &closed ? closed_skies : open_skies,
                                  positions, normals,
                                  hours_where(occupied, out.down, sensors == &closed),
                                  occupied_hours, out.year.lux, *replicates);
    const auto down_occupied = hours_where(occupied, out.down, true);
    out.occupied_down = int(std::count(down_occupied.begin(), down_occupied.end(), 1));
    out.open = annual_metrics(open_year, inside);
    return out;
}

} // namespace rad
