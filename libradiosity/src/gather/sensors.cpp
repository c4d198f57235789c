// Sensors: points files' lines, work-plane grids, one sensor's gather, and their figures.
#include "radiosity/sensors.hpp"

#include "radiosity/numbers.hpp"
#include "radiosity/text_input.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <vector>

namespace rad {

bool is_sensor_line(const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    return first != std::string::npos && text[first] != '#';
}

SensorPose parse_sensor_line(const std::string& text) {
    SensorPose sensor;
    const auto malformed = [&] {
        sensor.problem = "expected six numbers 'x y z dx dy dz', found " + quoted_prefix(text);
        return sensor;
    };
    std::istringstream words(text);
    std::string token;
    double v[6];
    int count = 0;
    while (words >> token) {
        if (count == 6 || !parse_number(token, v[count])) return malformed();
        ++count;
    }
    if (count != 6) return malformed();
    sensor.position = {v[0], v[1], v[2]};
    const Vec3 d{v[3], v[4], v[5]};
    const double len = length(d);
    if (!(len > 0) || !std::isfinite(len)) {
        sensor.problem = "the direction dx dy dz is zero: give the way the sensor faces";
        return sensor;
    }
    sensor.direction = {d[0] / len, d[1] / len, d[2] / len};
    return sensor;
}

Vec3 WorkPlaneGrid::position(long index) const {
    const long row = index / nx, column = index % nx;
    return {x0 + (column + 0.5) * (x1 - x0) / nx, y, z0 + (row + 0.5) * (z1 - z0) / nz};
}

WorkPlaneGrid parse_work_plane_grid(const std::string& text) {
    std::istringstream words(text);
    std::string token;
    std::vector<double> v;
    while (words >> token) {
        double value = 0;
        if (!parse_number(token, value))
            throw InputError("--grid: '" + token + "' is not a number");
        v.push_back(value);
    }
    if (v.size() != 7)
        throw InputError("--grid takes seven numbers \"x0 z0 x1 z1 y nx nz\", got " +
                         std::to_string(v.size()));
    const auto whole = [](double x) { return x >= 1 && x <= 100000 && x == std::floor(x); };
    if (!whole(v[5]) || !whole(v[6]) || v[5] * v[6] > 1e8)
        throw InputError("--grid: nx and nz are whole numbers from 1 to 100000 (at most 1e8 "
                         "points)");
    if (v[0] == v[2] || v[1] == v[3])
        throw InputError("--grid: x0 x1 and z0 z1 must differ (the grid has no area)");
    return {v[0], v[1], v[2], v[3], v[4], static_cast<long>(v[5]), static_cast<long>(v[6])};
}

Rgb luminaire_light(const Gatherer& gatherer, const LuminaireSet* luminaires, const Vec3& point,
                    const Vec3& normal) {
    Rgb sum{0, 0, 0};
    if (luminaires)
        for (const auto& g : luminaire_irradiance(*luminaires, point, normal, &gatherer.scene(),
                                                  {&gatherer.specular(), &gatherer.mirrors()}))
            for (int c = 0; c < 3; ++c) sum[c] += g[c];
    return sum;
}

Irradiance gather_sensor(const Gatherer& gatherer, const LuminaireSet* luminaires,
                         const Box& scene_box, const Vec3& position, const Vec3& direction,
                         std::uint64_t index, std::string& problem) {
    problem = out_of_reach(position, scene_box);
    if (!problem.empty()) return {};
    // The luminaires' direct light, exactly at the point (no error; it counts in the
    // accuracy's relative target).
    const Rgb known = luminaire_light(gatherer, luminaires, position, direction);
    auto result = gatherer.gather(position, direction, index, known);
    const double max_back = gatherer.options().max_back_fraction;
    if (result.sees_backs(max_back)) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "%.0f%% of the surfaces the point sees show their back: it is inside an "
                      "object, behind a surface, or faces into one (move it off the surface, or "
                      "turn it)",
                      100 * result.back_fraction);
        problem = text;
        return result;
    }
    for (std::size_t c = 0; c < 3; ++c) result.direct[c] += known[c];
    return result;
}

IlluminanceStats illuminance_stats(std::span<const double> lux) {
    IlluminanceStats s;
    double low = std::numeric_limits<double>::infinity(), high = 0, sum = 0;
    for (const double e : lux) {
        if (!std::isfinite(e)) {
            ++s.without_value;
            continue;
        }
        low = std::min(low, e), high = std::max(high, e), sum += e, ++s.count;
    }
    if (s.count == 0) return s;
    s.min = low, s.max = high, s.mean = sum / double(s.count);
    return s;
}

IlluminanceErrors illuminance_errors(std::span<const double> lux, std::span<const double> error) {
    IlluminanceErrors out;
    const auto stats = illuminance_stats(lux);
    if (stats.count == 0 || error.size() != lux.size()) return out;
    double squares = 0;
    std::size_t low = 0, high = 0;
    bool first = true;
    for (std::size_t k = 0; k < lux.size(); ++k) {
        if (!std::isfinite(lux[k])) continue;
        squares += error[k] * error[k];
        if (first || lux[k] < lux[low]) low = k;
        if (first || lux[k] > lux[high]) high = k;
        first = false;
    }
    out.mean = std::sqrt(squares) / double(stats.count);
    out.min = error[low];
    out.max = error[high];
    if (stats.mean > 0 && stats.min > 0) {
        const double a = out.min / stats.min, b = out.mean / stats.mean;
        out.u0 = stats.u0() * std::sqrt(a * a + b * b);
    } else if (stats.mean > 0) {
        out.u0 = out.min / stats.mean;
    }
    return out;
}

Judged judge_figure(double value, double error, double required, bool at_most) {
    Judged j;
    if (std::isnan(required)) return j;
    j.passes = at_most ? value <= required : value >= required;
    j.close = std::isfinite(error) && std::abs(value - required) <= 2 * error;
    return j;
}

} // namespace rad
