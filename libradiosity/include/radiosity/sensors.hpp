// Sensors: where illuminance is measured (a points file's "x y z dx dy dz" lines, a work
// plane's grid), what one sensor gathers (the solution's light and the luminaires' direct
// light, or why it cannot be gathered), and the figures lighting designers read of a set of
// them (Emin, Em, Emax, U0). rad-gather and rad-report share them, so a report's numbers are
// rad-gather's.
#pragma once
#include "radiosity/gather.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/vec.hpp"

#include <cstdint>
#include <limits>
#include <span>
#include <string>

namespace rad {

// One sensor: where it is, which way it faces (unit), and why it cannot be gathered ("" when
// it can).
struct SensorPose {
    Vec3 position{0, 0, 0}, direction{0, 0, 0};
    std::string problem;
};

// A points file's line that is a sensor: not blank, not a # comment.
bool is_sensor_line(const std::string& text);
// Parses "x y z dx dy dz" (rtrace -I); a malformed line or a zero direction sets `problem`
// instead of throwing, so that the lines before a bad one are still written, in order.
SensorPose parse_sensor_line(const std::string& text);

// rad-gather --grid "x0 z0 x1 z1 y nx nz": upward sensors at height y at the centres of
// nx x nz cells, rows of constant z from z0, x varying fastest.
struct WorkPlaneGrid {
    double x0 = 0, z0 = 0, x1 = 0, z1 = 0, y = 0;
    long nx = 0, nz = 0;
    long size() const { return nx * nz; }
    Vec3 position(long index) const;
};
// Throws InputError "--grid: ..." naming what is wrong.
WorkPlaneGrid parse_work_plane_grid(const std::string& text);

// The irradiance at a sensor (the solution's light, and `luminaires`' direct light exactly;
// null: none), or in `problem` why it has none: too far to trace, or inside an object or
// behind a surface. `index` seeds its random stream.
Irradiance gather_sensor(const Gatherer& gatherer, const LuminaireSet* luminaires,
                         const Box& scene_box, const Vec3& position, const Vec3& direction,
                         std::uint64_t index, std::string& problem);

// Emin, Em, Emax over the sensors with a value (NaN: none), and how many had none; all NaN
// when no sensor has a value.
struct IlluminanceStats {
    static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    long count = 0, without_value = 0;
    double min = kNone, mean = kNone, max = kNone;
    double u0() const { return count == 0 ? kNone : mean > 0 ? min / mean : 0; } // Emin / Em
    double min_over_max() const { return count == 0 ? kNone : max > 0 ? min / max : 0; }
};
IlluminanceStats illuminance_stats(std::span<const double> lux);

} // namespace rad
