// Calculation surfaces: the named rectangles lighting designers report (work planes, task
// areas, walls, ceilings, floors) with their grid of sensors by EN 12464-1's rule and the
// requirements the user sets, and the observers whose glare (UGR) is reported. One CSV file
// (formats/README.md, "Calculation surfaces") read by rad-gather --surfaces and rad-report.
#pragma once
#include "radiosity/error.hpp"
#include "radiosity/sensors.hpp"
#include "radiosity/vec.hpp"

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace rad {

enum class CalcKind {
    WorkPlane,
    Task,
    Wall,
    Ceiling,
    Floor,
    Observer,
    Camera,
    EscapeRoute,    // EN 1838: the centre line of a route along u, v its width
    OpenArea,       // EN 1838: an anti-panic area
    Cylindrical,    // EN 12464-1: cylindrical illuminance Ez over a horizontal area
    SemiCylindrical // the same, semi-cylindrical toward u
};
// "workplane", "task", "wall", "ceiling", "floor", "observer", "camera", "escape-route",
// "open-area", "cylindrical", "semi-cylindrical".
const char* calc_kind_name(CalcKind kind);
// Escape routes and open areas: lit by the emergency luminaires' direct light alone (EN 1838).
inline bool is_emergency(CalcKind kind) {
    return kind == CalcKind::EscapeRoute || kind == CalcKind::OpenArea;
}

inline constexpr double kNoRequirement = std::numeric_limits<double>::quiet_NaN();

// What the user requires of a surface (NaN: nothing): a maintained average, a uniformity
// Emin/Em, a minimum (lux) and a largest Emax/Emin (EN 1838's 40); of daylight, a mean daylight
// factor and an sDA300/50% at least, an ASE1000,250h at most (%).
struct Requirements {
    double em = kNoRequirement, u0 = kNoRequirement, emin = kNoRequirement;
    double max_over_min = kNoRequirement;
    double df = kNoRequirement, sda = kNoRequirement, ase = kNoRequirement;
    // Whether anything is required of the light (Em, U0, Emin), of daylight (DF, sDA, ASE).
    bool of_light() const {
        return !std::isnan(em) || !std::isnan(u0) || !std::isnan(emin) || !std::isnan(max_over_min);
    }
    bool of_daylight() const { return !std::isnan(df) || !std::isnan(sda) || !std::isnan(ase); }
};

// A rectangle from `corner` along the edges `u` and `v` (scene units); its sensors face
// u x v (right-handed: u along +x and v along -z face up).
struct CalcSurface {
    std::string name;
    FileLoc where;
    CalcKind kind = CalcKind::WorkPlane;
    Vec3 corner{0, 0, 0}, u{0, 0, 0}, v{0, 0, 0};
    double spacing_m = 0;             // 0: EN 12464-1's rule
    double border_m = kNoRequirement; // NaN: 0.5 m for a work plane, else 0
    Requirements required;
};

// An observer's eye and line of sight (scene units), with the UGR limit required (NaN: none).
struct CalcObserver {
    std::string name;
    FileLoc where;
    Vec3 position{0, 0, 0}, view{0, 0, 0}; // view: unit
    double ugr_limit = kNoRequirement;
};

// A view the report shows: the eye, the direction, the up vector and the horizontal angle
// (degrees); the vertical angle follows from the picture's shape.
struct CalcCamera {
    std::string name;
    FileLoc where;
    Vec3 position{0, 0, 0}, direction{0, 0, -1}, up{0, 1, 0};
    double angle_deg = 60;
};

struct CalcFile {
    std::string name;
    std::vector<CalcSurface> surfaces;
    std::vector<CalcObserver> observers;
    std::vector<CalcCamera> cameras;
};

// Reads a calculation-surfaces CSV. Throws InputError "FILE:LINE: ..." naming what is wrong
// and the fix (a missing or unknown column, a bad number, edges that span no area, a name used
// twice, ...).
CalcFile read_calc_file(const std::string& path);

// `text` as one CSV field: double-quoted (quotes doubled) when it holds a comma, a quote or
// blanks at its ends, as read_calc_file reads it back.
std::string csv_field(const std::string& text);

// EN 12464-1's grid spacing for a calculation area whose longer side is `longer_m` metres:
// 0.2 x 5^log10(d), at most 10 m.
double en12464_spacing(double longer_m);

// A surface's sensors: the calculation area (the surface less its border band) cut into
// columns x rows cells of at most the spacing, a sensor at each cell's centre; column along u
// varying fastest, rows along v.
struct SurfaceGrid {
    Vec3 origin{0, 0, 0}; // the calculation area's corner (scene units)
    Vec3 column_step{0, 0, 0}, row_step{0, 0, 0};
    Vec3 normal{0, 1, 0};
    long columns = 0, rows = 0;
    double width_m = 0, depth_m = 0;    // the calculation area, along u and v
    double spacing_m = 0, border_m = 0; // the spacing asked for (or the rule's), the band
    bool emergency = false;             // EN 1838: the emergency luminaires' direct light only
    bool cylindrical = false;           // Ez about the normal (u x v, up), not E
    bool semi = false;                  // E_sc toward `facing` (u), not Ez
    Vec3 facing{1, 0, 0};
    FileLoc where; // the surface's line
    long size() const { return columns * rows; }
    Vec3 position(long index) const {
        const long row = index / columns, column = index % columns;
        return origin + column_step * (column + 0.5) + row_step * (row + 0.5);
    }
    double area_m2() const { return width_m * depth_m; }
};
// An escape route's sensors lie on its centre line (one row along u, in the middle of v); an
// escape route's or open area's default spacing is at most kEmergencySpacing, an open area's
// default border EN 1838's 0.5 m.
// Throws InputError at the surface's line when the border leaves no area or the grid would
// exceed a million sensors.
SurfaceGrid surface_grid(const CalcSurface& surface, double metres_per_unit);

inline constexpr double kEmergencySpacing = 0.25; // m

// Every surface's grid, in the file's order.
std::vector<SurfaceGrid> surface_grids(const CalcFile& file, double metres_per_unit);

// Every grid's sensors in order, surface after surface (as gather_surfaces numbers them): where
// they are and the way they face. InputError at a surface's line when one is too far from the
// scene in `box` to trace (out_of_reach).
void surface_sensors(const CalcFile& file, const std::vector<SurfaceGrid>& grids, const Box& box,
                     std::vector<Vec3>& positions, std::vector<Vec3>& normals);

// Illuminance (lux) at every sensor of every grid, in order: surface by surface, each
// sensor's random stream from its index over all of them (so rad-gather --surfaces and
// rad-report give the same numbers). A sensor inside an object or behind a surface has NaN.
// Beside each value its standard error (lux); and the sensors that stopped at the ray budget
// before the accuracy asked for (GatherOptions::accuracy), by index in the grid.
// A cylindrical grid gets Ez (cylindrical.hpp) as its lux, and Eh beside it.
// An emergency grid (escape route, open area) gets EN 1838's figure instead: the direct light
// of the luminaires with an emergency share, each times that share, no reflected light, no
// error; InputError at the surface's line when `luminaires` has none.
struct GatheredSurface {
    std::vector<double> lux, error;
    // When most of the surface's points face the front of another surface within
    // kFacingTooClose (a wall's surface given facing into the wall, a hair in front of it):
    // the typical distance (m). Its points then read that surface's own light, not the light
    // falling on the place; NaN otherwise.
    double facing_distance_m = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> horizontal; // a cylindrical grid's Eh at each sensor (lux), else empty
    std::vector<long> at_budget;
};
class RayScene;
inline constexpr double kFacingTooClose = 0.05; // m

// facing_distance_m's rule: along the normal from up to 9 of the grid's points spread over it,
// the distance to the first surface if it is a front met within kFacingTooClose; the median
// of those when over half the points so meet one, else NaN.
double facing_surface_distance(const RayScene& scene, const SurfaceGrid& grid);

// How long gather_surfaces will take, projected from its first kEstimateSensors sensors (the
// threads allowed): `seconds` for all `sensors` on `surfaces`. The callback returns whether to
// go on (false: the surfaces come back as far as they were computed).
inline constexpr std::uint64_t kEstimateSensors = 256;
struct SensorsEstimate {
    double seconds = 0;
    std::uint64_t sensors = 0, measured = 0;
    std::size_t surfaces = 0;
    unsigned threads = 1; // the threads it was measured on (TBB's allowed parallelism)
};
using SensorsEstimated = std::function<bool(const SensorsEstimate&)>;
std::vector<GatheredSurface> gather_surfaces(const Gatherer& gatherer,
                                             const LuminaireSet* luminaires, const Box& scene_box,
                                             const std::vector<SurfaceGrid>& grids, bool quiet,
                                             const SensorsEstimated& estimated = {});

// The modelling index Ez/Eh over a cylindrical surface's sensors (those with both values):
// its mean and range; count 0 when none has both.
struct ModellingIndex {
    double mean = 0, min = 0, max = 0;
    long count = 0;
};
ModellingIndex modelling_index(const std::vector<double>& cylindrical,
                               const std::vector<double>& horizontal);

// InputError at the first surface of `file` a daylight solution cannot give: an escape route
// or open area (it has no emergency luminaires), a cylindrical or semi-cylindrical one (not
// computed for daylight yet).
void refuse_daylight_unsupported(const CalcFile& file);

// Whether `stats` meet `required` (true where nothing is required), and which margins lie
// within two standard errors (`errors`; none: not known), where the calculation cannot tell.
struct Verdict {
    bool em = true, u0 = true, emin = true, max_over_min = true;
    bool em_close = false, u0_close = false, emin_close = false;
    bool passes() const { return em && u0 && emin && max_over_min; }
    bool close() const { return em_close || u0_close || emin_close; }
};
Verdict judge(const IlluminanceStats& stats, const Requirements& required,
              const IlluminanceErrors& errors = {});

// Whether a surface's daylight meets the daylight requirements (true where nothing is
// required; sDA and ASE only when the year was computed). Shares in [0, 1], DF in %.
// `df_close`: the mean DF's margin lies within two of its standard errors (`mean_df_error`;
// NaN: not known).
// `sda_error`: sDA's standard error (a share; NaN: not known); its margin within two of them is
// `sda_close`.
struct DaylightVerdict {
    bool df = true, sda = true, ase = true;
    bool df_close = false, sda_close = false;
    bool passes() const { return df && sda && ase; }
    bool close() const { return df_close || sda_close; }
};
DaylightVerdict judge_daylight(double mean_df, const double* sda, const double* ase,
                               const Requirements& required,
                               double mean_df_error = std::numeric_limits<double>::quiet_NaN(),
                               double sda_error = std::numeric_limits<double>::quiet_NaN());

} // namespace rad
