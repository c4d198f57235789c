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

// The direct light of `luminaires` at a point facing `normal`, summed over their groups, seen
// through the gatherer's glass and in its planar mirrors; none without luminaires.
Rgb luminaire_light(const Gatherer& gatherer, const LuminaireSet* luminaires, const Vec3& point,
                    const Vec3& normal);

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

// The standard errors of those figures, from each sensor's own (`error`, beside `lux`; NaN
// where a sensor has none). The sensors' streams are independent, so Em's is the root of the
// sum of squares over the count; Emin's and Emax's are their sensors' own (the least of noisy
// values also leans low, which this does not count); U0's is by the usual first-order rule
// for a ratio. NaN where a figure is NaN or an error is not known.
struct IlluminanceErrors {
    static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    double min = kNone, mean = kNone, max = kNone, u0 = kNone;
};
IlluminanceErrors illuminance_errors(std::span<const double> lux, std::span<const double> error);

// A figure's verdict against a requirement it must reach (at least, or at most when
// `at_most`), and whether the margin lies within two standard errors, so that the calculation
// cannot tell (a NaN error: it is not known, so never "close").
struct Judged {
    bool passes = true, close = false;
};
Judged judge_figure(double value, double error, double required, bool at_most = false);

} // namespace rad
