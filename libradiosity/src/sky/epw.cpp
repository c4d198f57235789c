// The EPW reader (EnergyPlus Auxiliary Programs, "EnergyPlus Weather File (EPW) Data
// Dictionary", fields counted from 1: 1-5 date and time, 8 dew point, 10 pressure in Pa, 15
// direct normal and 16 diffuse horizontal radiation in Wh/m^2 over the hour, 9999 when
// missing).
#include "radfmt/names.hpp"
#include "radiosity/error.hpp"
#include "radiosity/text_input.hpp"
#include "radiosity/weather.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rad {
namespace {
constexpr int kHeaderLines = 8;
constexpr double kMissingRadiation = 9999;
constexpr double kMaxRadiation = 1500;

std::vector<std::string> fields_of(const std::string& line) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const auto comma = line.find(',', start);
        out.push_back(line.substr(start, comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

double number(const std::vector<std::string>& fields, std::size_t k, const FileLoc& at,
              const char* what) {
    std::string text = k < fields.size() ? fields[k] : "";
    while (!text.empty() && text.front() == ' ') text.erase(text.begin());
    while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
        !std::isfinite(value))
        throw InputError(at, std::string("field ") + std::to_string(k + 1) + " (" + what +
                                 ") is '" + quoted_prefix(text) + "', not a number");
    return value;
}

// A whole number field from `lo` to `hi` (a year, a month, a day, an hour).
int whole(const std::vector<std::string>& fields, std::size_t k, const FileLoc& at,
          const char* what, int lo, int hi) {
    const double v = number(fields, k, at, what);
    if (!(v >= lo && v <= hi) || v != std::floor(v))
        throw InputError(at, std::string("field ") + std::to_string(k + 1) + " (" + what +
                                 ") must be a whole number from " + std::to_string(lo) + " to " +
                                 std::to_string(hi));
    return int(v);
}

Location parse_location(const std::string& line, const FileLoc& at, std::string& place) {
    const auto f = fields_of(line);
    if (f.empty() || f[0] != "LOCATION" || f.size() < 10)
        throw InputError(at, "an EPW file starts with LOCATION,city,state,country,source,WMO,"
                             "latitude,longitude,time zone,elevation (this is no EPW file)");
    // As pages and summaries show it: without the quotes some writers put round it
    // ("VAN-NUYS-AP"), UTF-8 (a Latin-1 'ü' from older files made one).
    std::string_view city = f[1];
    if (city.size() >= 2 && city.front() == '"' && city.back() == '"')
        city = city.substr(1, city.size() - 2);
    place = radfmt::clean_name(city);
    Location l;
    l.latitude = number(f, 6, at, "latitude");
    l.longitude = number(f, 7, at, "longitude");
    l.time_zone = number(f, 8, at, "time zone");
    l.elevation = number(f, 9, at, "elevation");
    if (std::abs(l.latitude) > 90 || std::abs(l.longitude) > 180 || std::abs(l.time_zone) > 14)
        throw InputError(at, "latitude, longitude or time zone out of range (latitude -90..90, "
                             "longitude -180..180 east positive, time zone -12..14 hours)");
    return l;
}

// The days of `month` (1 to 12), of a leap year or not.
int days_in(int month, bool leap) {
    static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return kDays[month - 1] + (leap && month == 2 ? 1 : 0);
}

WeatherHour parse_hour(const std::string& line, const FileLoc& at, int& missing) {
    const auto f = fields_of(line);
    if (f.size() < 16)
        throw InputError(at, "a record has " + std::to_string(f.size()) +
                                 " fields; an EPW record has 35 (the date, hour, temperatures "
                                 "and radiation at least)");
    WeatherHour h;
    h.line = at.line;
    h.year = whole(f, 0, at, "year", 1, 9999);
    h.month = whole(f, 1, at, "month", 1, 12);
    h.day = whole(f, 2, at, "day", 1, 31);
    h.hour = whole(f, 3, at, "hour", 1, 24);
    if (h.day > days_in(h.month, true))
        throw InputError(at, "month " + std::to_string(h.month) + " has no day " +
                                 std::to_string(h.day));
    h.dew_point = number(f, 7, at, "dew point");
    const double pascal = number(f, 9, at, "pressure");
    h.pressure = pascal > 0 && pascal < 999999 ? pascal / 100 : 1010;
    h.direct_normal = number(f, 14, at, "direct normal radiation");
    h.diffuse_horizontal = number(f, 15, at, "diffuse horizontal radiation");
    bool absent = false;
    for (double* v : {&h.direct_normal, &h.diffuse_horizontal}) {
        // 9999 is EPW's "missing"; any other value over the solar constant (1361 W/m^2) is
        // no radiation on Earth, not a missing one (12345 or 1e300 were taken as missing).
        if (*v == kMissingRadiation) *v = 0, absent = true;
        if (!(*v >= 0 && *v <= kMaxRadiation)) {
            char text[40];
            std::snprintf(text, sizeof text, "%g", *v);
            throw InputError(at, std::string("radiation of ") + text +
                                     " W/m^2 (fields 15, 16: 0 to 1500, 9999 when missing)");
        }
    }
    if (absent) ++missing;
    // Field 19, the diffuse horizontal illuminance (EN 17037's median): read when it is a
    // plausible number, else not given (999999 is EPW's missing; an empty or odd field too).
    if (f.size() > 18) {
        char* end = nullptr;
        const double lux = std::strtod(f[18].c_str(), &end);
        if (end && *end == '\0' && end != f[18].c_str() && lux >= 0 && lux < 999999)
            h.diffuse_illuminance = lux;
    }
    if (h.dew_point > 70 || h.dew_point < -90) h.dew_point = 10; // 99.9: missing
    return h;
}
} // namespace

namespace {
// The records run hour by hour from 1 January 1:00 to 31 December 24:00, 29 February only in
// a file of 8784 (the year field may change from month to month: a typical year is made of
// months of several years). A file of 8760 records all at 1 January 12:00, or with 29 February
// in place of 31 December, was taken as a year.
void check_calendar(const Weather& w, const std::string& path) {
    const bool leap = w.hours.size() == 8784;
    std::size_t k = 0;
    for (int month = 1; month <= 12; ++month)
        for (int day = 1; day <= days_in(month, leap); ++day)
            for (int hour = 1; hour <= 24; ++hour, ++k) {
                const auto& h = w.hours[k];
                if (h.month == month && h.day == day && h.hour == hour) continue;
                char text[200];
                std::snprintf(text, sizeof text,
                              "the record for %d/%d hour %d stands where %d/%d hour %d belongs "
                              "(month/day; an EPW year runs hour by hour from 1/1 hour 1 to "
                              "12/31 hour 24%s)",
                              h.month, h.day, h.hour, month, day, hour,
                              leap ? ", with 2/29 in its 8784 records"
                                   : "; 2/29 only in a file of 8784 records");
                throw InputError(FileLoc{path, h.line}, text);
            }
}
} // namespace

int WeatherHour::day_of_year() const {
    static constexpr int kBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    return kBefore[month - 1] + day;
}

Weather read_epw(const std::string& path) {
    LineReader in(path);
    Weather w;
    w.path = path;
    std::string line;
    for (int k = 0; k < kHeaderLines; ++k) {
        if (!in.next(line))
            throw InputError(FileLoc{path, in.line_number()},
                             "the file ends within the EPW header (8 lines before the hours)");
        if (k == 0) w.location = parse_location(line, {path, in.line_number()}, w.place);
    }
    while (in.next(line)) {
        if (line.empty() || line == "\r") continue;
        w.hours.push_back(parse_hour(line, {path, in.line_number()}, w.missing));
    }
    if (w.hours.size() != 8760 && w.hours.size() != 8784)
        throw InputError(path + ": " + std::to_string(w.hours.size()) +
                         " hourly records; a year has 8760 (8784 in a leap year)");
    check_calendar(w, path);
    return w;
}

SunPosition sun_of_hour(const Weather& weather, const WeatherHour& hour) {
    Location at = weather.location;
    at.pressure = hour.pressure;
    return solar_position(at, {hour.year, hour.month, hour.day, hour.hour - 0.5});
}

} // namespace rad
