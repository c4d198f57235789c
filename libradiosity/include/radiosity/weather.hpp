// Weather files: EnergyPlus's EPW (the location, then one record an hour), read for what the
// skies need.
#pragma once
#include "radiosity/sky.hpp"

#include <string>
#include <vector>

namespace rad {

struct WeatherHour {
    int year = 0, month = 1, day = 1, hour = 1; // hour 1..24: the hour ending then
    double dew_point = 0;                       // degrees C
    double pressure = 1010;                     // mbar
    double direct_normal = 0;                   // W/m^2
    double diffuse_horizontal = 0;              // W/m^2
    double diffuse_illuminance = -1;            // lux (field 19); < 0: not given (999999)
    int line = 0;                               // in the file
    int day_of_year() const;
};

struct Weather {
    std::string path, place;
    Location location;
    std::vector<WeatherHour> hours;
    int missing = 0; // records whose radiation was missing (9999), taken as 0
};

// Reads an EPW file: its LOCATION line (latitude, longitude, time zone, elevation), the
// header's other 7 lines, then 8760 hourly records (8784 in a leap year). Refuses (InputError
// "FILE:LINE: ...") a missing or malformed LOCATION, a record of too few fields, a field
// that is no number, a month, day or hour out of range, or a count of records other than a
// year's.
Weather read_epw(const std::string& path);

// The sun at the middle of an hour's interval (local standard time hour - 0.5).
SunPosition sun_of_hour(const Weather& weather, const WeatherHour& hour);

} // namespace rad
