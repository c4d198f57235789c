// A year of daylight at sensors from a weather file: hourly Perez skies through the sensors'
// daylight coefficients, the sun's beam traced at each sensor for each hour (as Radiance's
// five-phase method does, rather than smeared over a sky patch).
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/text_input.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

namespace rad {
namespace {
// Directions per sky patch for the hourly patch means: 4 x 4 (3 degrees apart on Tregenza's
// patches), where one sky's 16 x 16 would cost a year 16 times as much.
constexpr int kHourlySide = 4;
// The sun's zenith at an hour's middle past which the whole hour is night (8 degrees under the
// horizon: it moves at most 15 degrees an hour): whatever light the record gives, it is dark.
constexpr double kNightZenith = 98;

} // namespace

std::optional<Sky> hour_sky(const Weather& weather, const WeatherHour& h, const SkyFrame& frame,
                            double ground, bool* night_light) {
    const auto sun = sun_of_hour(weather, h);
    if (night_light) *night_light = false;
    if (sun.zenith > kNightZenith) {
        if (night_light) *night_light = h.direct_normal > 0 || h.diffuse_horizontal > 0;
        return std::nullopt;
    }
    if (h.diffuse_horizontal <= 0 && (h.direct_normal <= 0 || sun.zenith >= 90))
        return std::nullopt;
    return Sky::perez(h.direct_normal, h.diffuse_horizontal, sun, h.day_of_year(), h.dew_point,
                      frame, ground);
}

Sky weather_file_sky(const std::string& path, const std::string& date, const std::string& time,
                     const SkyFrame& frame, double ground) {
    if (date.empty() || time.empty())
        throw InputError("--sky epw:" + path +
                         " is the sky of one of its hours: give --date and "
                         "--time");
    const auto weather = read_epw(path);
    const auto when = parse_local_time(date, time);
    // The record of the hour ending at or after the time (EPW's hour 1 is 00:00 to 01:00).
    const int ending = std::clamp(int(std::ceil(when.hour)), 1, 24);
    for (const auto& h : weather.hours)
        if (h.month == when.month && h.day == when.day && h.hour == ending) {
            if (auto sky = hour_sky(weather, h, frame, ground, nullptr)) return *sky;
            auto dark = Sky::perez(0, 0, sun_of_hour(weather, h), h.day_of_year(), h.dew_point,
                                   frame, ground);
            return dark;
        }
    char text[64];
    std::snprintf(text, sizeof text, "%02d-%02d, the hour ending %02d:00", when.month, when.day,
                  ending);
    throw InputError(path + ": no record for " + text + " (a weather file holds one year)");
}

HourlySkies hourly_skies(const Weather& weather, const SkyPatches& patches, const SkyFrame& frame,
                         double ground) {
    HourlySkies out;
    out.count = patches.count();
    const std::size_t hours = weather.hours.size();
    out.direct.assign(hours * out.count, 0.0f);
    out.reflected.assign(hours * out.count, 0.0f);
    out.sun.assign(hours, Vec3{0, 1, 0});
    out.sun_lux.assign(hours, 0.0);
    out.adjusted.assign(hours, 0);
    out.night_light.assign(hours, 0);
    out.sun_patch.assign(hours, -1);
    out.beam_luminance.assign(hours, 0.0);
    const auto cells = patches.cells(frame, kHourlySide); // once for the year
    tbb::parallel_for(std::size_t(0), hours, [&](std::size_t t) {
        bool night_light = false;
        const auto lit = hour_sky(weather, weather.hours[t], frame, ground, &night_light);
        out.night_light[t] = night_light;
        if (!lit) return;
        const auto& sky = *lit;
        out.adjusted[t] = !sky.adjusted().empty();
        const auto mean = patches.mean_luminance(sky, cells);
        for (std::size_t s = 0; s < out.count; ++s)
            out.direct[t * out.count + s] = out.reflected[t * out.count + s] = float(mean[s]);
        if (const auto beam = sun_patch(patches, sky)) {
            out.sun[t] = sky.sun_direction();
            out.sun_lux[t] = sky.sun_normal_illuminance();
            // The beam's reflected light comes from the patch the sun is in.
            out.reflected[t * out.count + beam->patch] += float(beam->luminance);
            out.sun_patch[t] = std::int64_t(beam->patch);
            out.beam_luminance[t] = beam->luminance;
        }
    });
    return out;
}

namespace {

// A note on the hours `flags` marks: "FILE: N hour(s) <what> (first: line L, MM-DD HH:00, DNI
// d, DHI h W/m^2)<then>"; empty when none is.
std::string flagged_hours_note(const Weather& weather, const std::vector<std::uint8_t>& flags,
                               const char* what, const char* then) {
    const auto first = std::find(flags.begin(), flags.end(), 1);
    if (first == flags.end()) return "";
    const auto& h = weather.hours[std::size_t(first - flags.begin())];
    char text[400];
    std::snprintf(text, sizeof text,
                  "%s: %ld hour(s) %s (first: line %d, %02d-%02d %02d:00, DNI %g, DHI %g W/m^2)%s",
                  weather.path.c_str(), long(std::count(flags.begin(), flags.end(), 1)), what,
                  h.line, h.month, h.day, h.hour, h.direct_normal, h.diffuse_horizontal, then);
    return text;
}
} // namespace

namespace {
// One sensor's replicates of the year: replicate b adds to each hour batch b's deviation from
// the batches' mean, scaled to the size of the mean's own error (1 / sqrt(B - 1)): a draw of
// the error the estimate has, the same rays for every hour (so its hours' errors are as
// correlated as the estimate's). Per replicate, adds the shares of occupied hours (of
// `occupied_hours`) at 300 lx or more and within 100 to 3000 lx, over the hours `counted`
// marks (the occupied hours this solution lit: all of them, or a window state's).
void sensor_replicates(const DaylightSensors& sensors, const HourlySkies& skies,
                       const std::vector<std::uint8_t>& counted, int occupied_hours,
                       const Vec3& position, const Vec3& normal, std::size_t k,
                       const std::vector<float>& lux, std::size_t n, AnnualReplicates& out) {
    int batches = 0;
    const auto c = sensors.reflected_batch_coefficients(position, normal, k, batches);
    if (batches < 2 || batches != out.batches || occupied_hours == 0) return;
    const std::size_t count = skies.count, hours = counted.size(), b_count = std::size_t(batches);
    const double scale = 1 / std::sqrt(double(batches - 1));
    std::vector<double> da(b_count, 0.0), udi(b_count, 0.0), r(b_count, 0.0);
    for (std::size_t t = 0; t < hours; ++t) {
        if (!counted[t]) continue;
        const float* lr = &skies.reflected[t * count];
        double mean = 0;
        for (std::size_t b = 0; b < b_count; ++b) {
            double sum = 0;
            for (std::size_t s = 0; s < count; ++s) sum += c[b * count + s] * lr[s];
            mean += (r[b] = sum) / double(b_count);
        }
        for (std::size_t b = 0; b < b_count; ++b) {
            const double value = lux[t * n + k] + (r[b] - mean) * scale;
            da[b] += value >= 300;
            udi[b] += value >= 100 && value <= 3000;
        }
    }
    for (std::size_t b = 0; b < b_count; ++b) {
        out.da300[k * b_count + b] += da[b] / occupied_hours;
        out.udi_useful[k * b_count + b] += udi[b] / occupied_hours;
    }
}

int count_of(const std::vector<std::uint8_t>& flags) {
    return int(std::count(flags.begin(), flags.end(), 1));
}

// The replicates' storage for n sensors, zero (nothing added yet).
void start_replicates(const DaylightSensors& sensors, std::size_t n, AnnualReplicates& out) {
    const int batches = sensors.reflected_batch_count();
    out.batches = batches >= 2 ? batches : 0;
    out.da300.assign(n * std::size_t(out.batches), 0.0);
    out.udi_useful.assign(n * std::size_t(out.batches), 0.0);
}
} // namespace

void add_annual_replicates(const DaylightSensors& sensors, const HourlySkies& skies,
                           const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                           const std::vector<std::uint8_t>& counted, int occupied_hours,
                           const std::vector<float>& lux, AnnualReplicates& replicates) {
    const std::size_t n = positions.size();
    if (replicates.batches == 0) start_replicates(sensors, n, replicates);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
        sensor_replicates(sensors, skies, counted, occupied_hours, positions[k], normals[k], k, lux,
                          n, replicates);
    });
}

radfmt::AnnualData annual_illuminance(const DaylightSensors& sensors,
                                      const std::vector<Vec3>& positions,
                                      const std::vector<Vec3>& normals, const Weather& weather,
                                      const std::vector<std::uint8_t>& occupied, double ground,
                                      bool quiet, std::vector<std::string>* notes,
                                      AnnualReplicates* replicates) {
    return annual_illuminance(sensors,
                              hourly_skies(weather, sensors.patches(), sensors.frame(), ground),
                              positions, normals, weather, occupied, quiet, notes, replicates);
}

radfmt::AnnualData annual_illuminance(const DaylightSensors& sensors, const HourlySkies& skies,
                                      const std::vector<Vec3>& positions,
                                      const std::vector<Vec3>& normals, const Weather& weather,
                                      const std::vector<std::uint8_t>& occupied, bool quiet,
                                      std::vector<std::string>* notes,
                                      AnnualReplicates* replicates) {
    if (skies.count != sensors.patches().count() || skies.sun.size() != weather.hours.size())
        throw InternalError("annual_illuminance: the skies are not of these sensors' sky patches "
                            "and the weather's hours");
    if (notes)
        for (auto note :
             {flagged_hours_note(weather, skies.night_light,
                                 "give light while the sun is below the horizon all hour",
                                 ": the file's fault, counted as dark"),
              flagged_hours_note(weather, skies.adjusted,
                                 "whose Perez distribution is negative over the whole sky at the "
                                 "hour's brightness were taken at the least brightness that gives "
                                 "a sky",
                                 "")})
            if (!note.empty()) notes->push_back(std::move(note));
    const std::size_t n = positions.size(), hours = weather.hours.size(), count = skies.count;
    radfmt::AnnualData year;
    year.positions = positions;
    year.normals = normals;
    year.occupied = occupied;
    for (const auto& h : weather.hours)
        year.hours.push_back(std::uint32_t(h.month * 10000 + h.day * 100 + h.hour));
    year.lux.assign(hours * n, 0.0f);
    year.sun_lux.assign(hours * n, 0.0f);
    if (replicates) start_replicates(sensors, n, *replicates);
    const int occupied_hours = count_of(occupied);
    Progress progress("rad-gather year", n, quiet);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
        const auto c = sensors.coefficients(positions[k], normals[k], k);
        std::vector<float> direct(c.direct.begin(), c.direct.end());
        std::vector<float> reflected(c.reflected.begin(), c.reflected.end());
        for (std::size_t t = 0; t < hours; ++t) {
            const float* ld = &skies.direct[t * count];
            const float* lr = &skies.reflected[t * count];
            float lux = 0;
            for (std::size_t s = 0; s < count; ++s) lux += direct[s] * ld[s] + reflected[s] * lr[s];
            const double sun = skies.sun_lux[t] > 0 ? sensors.sun(positions[k], normals[k],
                                                                  skies.sun[t], skies.sun_lux[t])
                                                    : 0.0;
            year.lux[t * n + k] = lux + float(sun);
            year.sun_lux[t * n + k] = float(sun);
        }
        if (replicates)
            sensor_replicates(sensors, skies, occupied, occupied_hours, positions[k], normals[k], k,
                              year.lux, n, *replicates);
        progress.advance(1);
    });
    progress.finish();
    return year;
}

std::vector<std::uint8_t> default_occupancy(const Weather& weather) {
    std::vector<std::uint8_t> out;
    for (const auto& h : weather.hours) out.push_back(h.hour > 8 && h.hour <= 18); // 08-18
    return out;
}

std::vector<std::uint8_t> read_hourly_flags(const std::string& path, std::size_t hours,
                                            std::string_view what) {
    LineReader in(path);
    std::vector<std::uint8_t> out;
    std::string line;
    while (in.next(line)) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        const auto last = line.find_last_not_of(" \t\r");
        const auto word = line.substr(first, last - first + 1);
        if (word != "0" && word != "1")
            throw InputError(FileLoc{path, in.line_number()},
                             std::string(std::strchr("aeiou", what.front()) ? "an " : "a ") +
                                 std::string(what) +
                                 " line is 0 or 1 (one a line for each hour of the year), not '" +
                                 quoted_prefix(word) + "'");
        out.push_back(word == "1");
    }
    if (out.size() != hours)
        throw InputError(path + ": " + std::to_string(out.size()) + " hours of " +
                         std::string(what) + "; the weather file has " + std::to_string(hours));
    return out;
}

std::vector<std::uint8_t> read_occupancy(const std::string& path, std::size_t hours) {
    const auto out = read_hourly_flags(path, hours, "occupancy");
    // sDA, ASE and DA are shares of occupied hours: with none they mean nothing (a 0% and a
    // "fails" would be a verdict over no hour at all).
    if (std::find(out.begin(), out.end(), 1) == out.end())
        throw InputError(path + ": no hour is occupied (every line is 0): sDA, ASE and DA are "
                                "shares of the occupied hours; mark the hours the space is used "
                                "with 1");
    return out;
}

} // namespace rad
