// Skies, places, times and suns as a command line gives them.
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/sky.hpp"
#include "radiosity/weather.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

namespace rad {
namespace {
constexpr double kDefaultSkyLux = 10000;

std::vector<double> numbers_of(const std::string& text, char separator, const std::string& what) {
    std::vector<double> out;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, separator)) {
        double v = 0;
        if (!parse_number(part, v) || !std::isfinite(v))
            throw InputError(what + ": '" + part + "' is not a number");
        out.push_back(v);
    }
    return out;
}

// The ranges a real sky keeps, with room: past them a value is a typo, and past them light
// products overflow (1e308 lux gave NaN lux).
constexpr double kMaxSkyLuminance = 1e6; // cd/m^2: a bright overcast sky is about 1e4
constexpr double kMaxSkyLux = 1e6;       // lux: sun and sky together stay under 1.5e5
constexpr double kMaxIrradiance = 1500;  // W/m^2: the solar constant is 1361

// `value` within [0, high], or InputError naming the option and the range.
double in_range(double value, double high, const std::string& what) {
    if (value >= 0 && value <= high) return value;
    char text[200];
    std::snprintf(text, sizeof text, ": %.4g is outside 0 to %.4g", value, high);
    throw InputError(what + text);
}

int days_in_month(int year, int month) {
    static const int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return month == 2 && leap ? 29 : days[month - 1];
}

const char* kSkyForms = "uniform[:L], cie-overcast[:LUX], cie:TYPE[:LUX] (TYPE 1..15), "
                        "perez:DNI,DHI (W/m^2), clear, partly-cloudy or overcast";
} // namespace

Sky parse_sky(const std::string& spec, const SunPosition* sun, int day_of_year,
              const SkyFrame& frame, double ground) {
    const auto colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
    const auto need_sun = [&] {
        if (!sun)
            throw InputError("--sky " + spec +
                             " needs the sun: --sun ALT,AZ, or --date, --time "
                             "and --location (or --epw for the place)");
        return *sun;
    };
    if (name == "uniform") {
        const auto v = rest.empty() ? std::vector<double>{kDefaultSkyLux / std::numbers::pi}
                                    : numbers_of(rest, ',', "--sky uniform:L");
        if (v.size() != 1) throw InputError("--sky uniform:L takes one luminance (cd/m^2)");
        return Sky::uniform(in_range(v[0], kMaxSkyLuminance, "--sky uniform:L (cd/m^2)"), frame,
                            ground);
    }
    if (name == "cie-overcast") {
        const auto v = rest.empty() ? std::vector<double>{kDefaultSkyLux}
                                    : numbers_of(rest, ',', "--sky cie-overcast:LUX");
        if (v.size() != 1) throw InputError("--sky cie-overcast:LUX takes one illuminance");
        return Sky::cie_overcast(in_range(v[0], kMaxSkyLux, "--sky cie-overcast:LUX"), frame,
                                 ground);
    }
    if (name == "cie") {
        const auto v = numbers_of(rest, ':', "--sky cie:TYPE[:LUX]");
        if (v.empty() || v.size() > 2 || v[0] != std::floor(v[0]))
            throw InputError("--sky cie:TYPE[:LUX]: TYPE is 1..15, LUX the sky's horizontal "
                             "illuminance");
        const double lux =
            v.size() > 1 ? in_range(v[1], kMaxSkyLux, "--sky cie:TYPE:LUX") : kDefaultSkyLux;
        return Sky::cie_standard(int(v[0]), need_sun(), lux, frame, ground);
    }
    if (name == "perez") {
        const auto v = numbers_of(rest, ',', "--sky perez:DNI,DHI");
        if (v.size() != 2)
            throw InputError("--sky perez:DNI,DHI takes direct normal and diffuse horizontal "
                             "irradiance (W/m^2)");
        return Sky::perez(in_range(v[0], kMaxIrradiance, "--sky perez: DNI (W/m^2)"),
                          in_range(v[1], kMaxIrradiance, "--sky perez: DHI (W/m^2)"), need_sun(),
                          day_of_year, 10, frame, ground);
    }
    if (name == "clear" || name == "partly-cloudy" || name == "overcast") {
        if (!rest.empty()) throw InputError("--sky " + name + " takes nothing after it");
        const auto day = name == "clear"           ? Sky::Day::clear
                         : name == "partly-cloudy" ? Sky::Day::partly_cloudy
                                                   : Sky::Day::overcast;
        return Sky::of_day(day, need_sun(), frame, ground);
    }
    throw InputError("--sky '" + spec + "' is not known: give " + kSkyForms);
}

Location parse_location(const std::string& text) {
    const auto v = numbers_of(text, ',', "--location");
    if (v.size() < 3 || v.size() > 4 || std::abs(v[0]) > 90 || std::abs(v[1]) > 180 ||
        std::abs(v[2]) > 14)
        throw InputError("--location takes LAT,LON,TZ[,ELEVATION]: degrees north (-90..90), "
                         "degrees east (-180..180), hours east of UTC (-12..14), metres");
    Location l;
    l.latitude = v[0];
    l.longitude = v[1];
    l.time_zone = v[2];
    if (v.size() == 4) l.elevation = v[3];
    if (!(l.elevation >= -500 && l.elevation <= 9000)) {
        char message[120];
        std::snprintf(message, sizeof message,
                      "--location: an elevation of %.4g m is outside -500 to 9000 m", l.elevation);
        throw InputError(message);
    }
    return l;
}

LocalTime parse_local_time(const std::string& date, const std::string& time) {
    int y = 0, mo = 0, d = 0, h = 0, mi = 0;
    char tail = 0;
    if (std::sscanf(date.c_str(), "%d-%d-%d%c", &y, &mo, &d, &tail) != 3 || y < 1 || y > 9999 ||
        mo < 1 || mo > 12 || d < 1 || d > days_in_month(y, mo))
        throw InputError("--date '" + date +
                         "': give YYYY-MM-DD, a day of the calendar (year 1 to 9999)");
    if (std::sscanf(time.c_str(), "%d:%d%c", &h, &mi, &tail) != 2 || h < 0 || h > 24 || mi < 0 ||
        mi > 59 || (h == 24 && mi > 0))
        throw InputError("--time '" + time +
                         "': give HH:MM from 00:00 to 24:00, local standard time");
    return {y, mo, d, h + mi / 60.0};
}

SunPosition parse_sun(const std::string& text) {
    const auto v = numbers_of(text, ',', "--sun");
    if (v.size() != 2 || v[0] < -90 || v[0] > 90)
        throw InputError("--sun takes ALT,AZ: altitude -90..90 and azimuth from north towards "
                         "east, degrees");
    SunPosition s;
    s.zenith = 90 - v[0];
    s.azimuth = v[1];
    return s;
}

std::optional<SunPosition> sun_from(const SunArguments& a, int& day_of_year) {
    day_of_year = 172;
    if (a.date.empty() != a.time.empty()) throw InputError("--date and --time go together");
    if (!a.sun.empty() && !a.date.empty()) throw InputError("--sun or --date/--time, not both");
    if (!a.sun.empty()) return parse_sun(a.sun);
    if (a.date.empty()) return std::nullopt;
    Location where;
    if (!a.location.empty())
        where = parse_location(a.location);
    else if (!a.epw.empty())
        where = read_epw(a.epw).location;
    else
        throw InputError("--date needs --location LAT,LON,TZ (or --epw for the place)");
    const auto when = parse_local_time(a.date, a.time);
    WeatherHour h;
    h.month = when.month;
    h.day = when.day;
    day_of_year = h.day_of_year();
    return solar_position(where, when);
}

} // namespace rad
