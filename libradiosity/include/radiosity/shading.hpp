// Operable shading over a year: a window with two states (open, and shaded: blinds down, a
// second glazing), each state its own solution of the same geometry (rad-mesh --transmittance
// on the window's material), and a rule choosing the state hour by hour. IES LM-83-12's rule:
// the blinds are down in any hour when more than 2% of the sensors get 1000 lx or more of
// direct sun with them up; sDA is computed with the blinds as operated, ASE with them up.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/weather.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

struct ShadingRule {
    enum class Kind { sun, schedule };
    Kind kind = Kind::sun;
    // sun: the blinds go down when more than `share` of the sensors get `lux` or more of the
    // open state's direct sun (LM-83: 1000 lx, 2%).
    double lux = 1000, share = 0.02;
    std::vector<std::uint8_t> schedule; // schedule: per hour, 1 where the blinds are down
    std::string text;                   // as given ("lm83", "sun:1000:2", "schedule:FILE")
    // "LM-83's rule (blinds down when more than 2% of the sensors get 1000 lx or more of
    // direct sun)", "the schedule FILE".
    std::string describe() const;
};

// "lm83" (sun:1000:2), "sun:LUX:PERCENT", or "schedule:FILE" (one 0 or 1 a line for each of
// the year's `hours`, # comments and blank lines skipped; 1: blinds down). InputError naming
// the text, or FILE:LINE, otherwise.
ShadingRule parse_shading_rule(std::string_view text, std::size_t hours);

// Per hour, the share of the sensors `judged` marks (one flag a sensor) that get `lux` or more
// of the open year's direct sun (AnnualData::sun_lux); 0 when none is judged.
std::vector<double> sunlit_shares(const radfmt::AnnualData& open,
                                  std::span<const std::uint8_t> judged, double lux);

// Per hour, 1 where the shaded state is used. The sun rule judges the open year's direct sun
// (AnnualData::sun_lux) at the sensors `judged` marks (one flag a sensor: sensors inside
// objects, or outside the group the rule watches, are 0); an hour with no sensor judged stays
// open.
std::vector<std::uint8_t> shaded_hours(const ShadingRule& rule, const radfmt::AnnualData& open,
                                       std::span<const std::uint8_t> judged);
// The same from the hours' sunlit shares already taken (sunlit_shares at the rule's lux).
std::vector<std::uint8_t> shaded_hours(const ShadingRule& rule, const std::vector<double>& shares);

// The year as operated: each hour's illuminance from the state `shaded` marks for it, the
// direct sun the open state's at every hour (LM-83 computes ASE with the blinds up), so
// annual_metrics of it gives sDA as operated and ASE as LM-83 defines it. The two years must be
// of the same sensors and hours (InternalError otherwise).
radfmt::AnnualData operated_year(const radfmt::AnnualData& open, const radfmt::AnnualData& closed,
                                 const std::vector<std::uint8_t>& shaded);

// A year with the window operated: both states' years (annual_illuminance, `open` and `closed`
// the sensors of each state's solution), the rule's hours judged at the sensors `judged`
// marks, the year as operated, and with `replicates` each state's replicates over the
// occupied hours it lit (add_annual_replicates). `inside` as annual_metrics takes it, for the
// open year's figures. `notes` as annual_illuminance's (the open state's year).
struct OperatedYear {
    radfmt::AnnualData year;        // as operated_year gives it
    std::string rule;               // the rule's ShadingRule::describe
    std::vector<std::uint8_t> down; // per hour: the shaded state used
    std::vector<double> sunlit;     // per hour: sunlit_shares at the rule's lux
    int occupied_down = 0;          // occupied hours with the shaded state
    AnnualMetrics open;             // the year with the blinds up all year
};
OperatedYear operated_annual(const DaylightSensors& open, const DaylightSensors& closed,
                             const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                             const Weather& weather, const std::vector<std::uint8_t>& occupied,
                             double ground, const ShadingRule& rule,
                             std::span<const std::uint8_t> judged,
                             std::span<const std::uint8_t> inside, bool quiet = true,
                             std::vector<std::string>* notes = nullptr,
                             AnnualReplicates* replicates = nullptr);

} // namespace rad
