// EN 17037's daylight provision by its daylight factor method: the target and minimum
// illuminances of its three levels turned into daylight factors for the place (over its median
// external diffuse illuminance), and the shares of the reference plane that reach them.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/weather.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rad {

// E_v,d,med: the median of the diffuse horizontal illuminance over the year's daylight hours,
// the half of the year's hours with the most (the median of the 4380 highest hourly values of
// 8760). From the file's own diffuse horizontal illuminance (EPW field 19) when every hour
// gives it, else from its diffuse radiation by Perez's luminous efficacy (the all-weather
// sky's horizontal illuminance). `source` says which.
struct MedianDiffuse {
    double lux = 0;
    std::string source;
};
MedianDiffuse median_external_diffuse_illuminance(const Weather& weather);

// One level: a target illuminance E_T over half of the plane and a minimum E_TM over 95% of
// it, as daylight factors D = E / E_v,d,med (%), the shares of the points at or above each,
// and whether both are met.
struct En17037Level {
    const char* name = "";
    double target_lux = 0, minimum_lux = 0;
    double target_df = 0, minimum_df = 0;       // %
    double target_share = 0, minimum_share = 0; // of the points with a value
    bool met = false;
};
struct En17037Provision {
    double median_lux = 0;
    std::array<En17037Level, 3> levels; // minimum (300/100 lx), medium (500/300), high (750/500)
    // The highest level met ("none" when not the minimum).
    std::string achieved() const;
};
// `factors`: the reference plane's daylight factors (%; NaN: no value, left out).
En17037Provision en17037_daylight_provision(std::span<const double> factors, double median_lux);

// The illuminance method. EN 17037's daylight hours: the half of the year's hours with the
// most diffuse horizontal illuminance (those E_v,d,med is the median of; ties by order), 1
// each.
std::vector<std::uint8_t> en17037_daylight_hours(const Weather& weather);

// One level by the year's illuminance: the shares of the daylight hours in which the target
// E_T is reached over half of the plane's points, and the minimum E_TM over 95% of them (the
// standard's F_plane, hour by hour); met when both shares are at least half (F_time 50%).
struct En17037HourLevel {
    const char* name = "";
    double target_lux = 0, minimum_lux = 0;
    double target_hours = 0, minimum_hours = 0; // shares of the daylight hours
    bool met = false;
};
struct En17037Hourly {
    int daylight_hours = 0;
    std::size_t points = 0; // the plane's points with a value
    std::array<En17037HourLevel, 3> levels;
    std::string achieved() const; // the highest level met, "none" when not the minimum
};
// `plane`: one flag per sensor of `year` (1: a point of the reference plane with a value);
// `daylight_hours`: one flag per hour of `year` (en17037_daylight_hours).
En17037Hourly en17037_illuminance_method(const radfmt::AnnualData& year,
                                         std::span<const std::uint8_t> plane,
                                         const std::vector<std::uint8_t>& daylight_hours);

} // namespace rad
