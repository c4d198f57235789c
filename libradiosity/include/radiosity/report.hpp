// The lighting report (rad-report): one self-contained HTML page, printable at A4, of the
// calculation surfaces' figures against their requirements with false-colour isolux plans,
// the luminaires' schedule, polar curves and power density, and the observers' glare. Every
// number comes from what the caller computed (the same functions rad-gather calls).
#pragma once
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/daylight_glare.hpp"
#include "radiosity/en17037.hpp"
#include "radiosity/glare.hpp"
#include "radiosity/lighting_energy.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/luminance_map.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rad {

// A daylight solution's figures on a surface: the daylight factor under the CIE overcast
// sky, and with a weather file the year's metrics.
struct SurfaceDaylight {
    std::vector<double> factor;       // % per sensor
    std::vector<double> factor_error; // its standard error (the reflected light's), % per sensor
    DaylightFactorSummary summary;
    double mean_error = std::numeric_limits<double>::quiet_NaN(); // of summary.mean
    std::vector<long> at_budget; // sensors that stopped at the ray budget before the accuracy
    bool annual = false;
    std::vector<double> da300;  // % of occupied hours, per sensor
    AnnualMetrics metrics;      // this surface's
    AnnualErrors metric_errors; // their standard errors (the jackknife's)
    // A work plane with a year: EN 17037's daylight provision by the daylight factor method.
    std::optional<En17037Provision> en17037;
    // And by the year's illuminance over EN 17037's daylight hours.
    std::optional<En17037Hourly> en17037_hourly;
    std::string median_source; // where the median external diffuse illuminance came from
    DaylightVerdict verdict;   // against the surface's DF, sDA and ASE requirements
};

// A piece of line on a surface's plan, in metres along u and v from its calculation area's
// corner (the plan's own coordinates).
struct PlanSegment {
    double u0 = 0, v0 = 0, u1 = 0, v1 = 0;
    bool glass = false; // a cut through a pane or other glass (a window): drawn as glazing
};
// Where the mesh's surfaces cross a horizontal calculation surface's plane (a centimetre in
// front of it): walls, partitions, cabinets cut as a designer's plan cuts them, clipped to the
// surface with its border. None for a surface that is not horizontal.
std::vector<PlanSegment> plan_cut(const radfmt::MeshData& mesh, const SurfaceGrid& grid,
                                  double metres_per_unit);

struct ReportSurface {
    CalcSurface surface;
    SurfaceGrid grid;
    std::vector<PlanSegment> cut;   // the room cut at its plane (plan_cut)
    std::vector<double> lux;        // per sensor, NaN: none (empty for daylight)
    std::vector<double> lux_error;  // each sensor's standard error (lux)
    std::vector<double> horizontal; // a cylindrical surface's Eh per sensor (lux), else empty
    std::vector<long> at_budget;    // sensors that stopped at the ray budget before the accuracy
    double facing_distance_m = std::numeric_limits<double>::quiet_NaN(); // GatheredSurface's
    IlluminanceStats stats;
    IlluminanceErrors errors;
    Verdict verdict;
    std::optional<SurfaceDaylight> daylight;
};

struct ReportObserver {
    CalcObserver observer;
    double background = 0; // Lb, cd/m^2
    ObserverGlare glare;
};

// An observer's daylight glare over a year (a daylight solution with a weather file).
struct ReportDaylightGlare {
    CalcObserver observer;
    GlareYear year;
};

// A view of the lit scene, rendered as rad-shade renders it with `command`'s options.
struct ReportView {
    std::string name, command;
    std::vector<std::uint8_t> png;
    std::vector<std::uint8_t> thumbnail_png; // at half size, for the title block (may be empty)
    int width = 0, height = 0;
    // Its luminance: the false-colour picture (rad-shade --falsecolor's bytes), its scale,
    // and each surface's luminance (--luminance-table).
    std::vector<std::uint8_t> falsecolor_png;
    LuminanceScale scale;
    std::vector<SurfaceLuminance> surfaces;
};

// The room as the mesh has it: its bounding size (x, y, z; m) and each material's area (m^2)
// and luminous reflectance.
struct RoomMaterial {
    std::string name;
    double area_m2 = 0, reflectance = 0;
    bool emits = false;
};
struct RoomSummary {
    Vec3 size_m{0, 0, 0};
    Box bounds;                          // scene units
    std::vector<RoomMaterial> materials; // those some patch uses, in the mesh's order
};
RoomSummary room_summary(const radfmt::MeshData& mesh, double metres_per_unit);

struct ReportInput {
    std::string project, date, producer;                     // producer: "rad-report 0.1.0"
    std::string client, designer;                            // the title block's (may be empty)
    std::vector<std::pair<std::string, std::string>> inputs; // path, hash
    std::vector<std::string> provenance;                     // the solution's commands
    std::string method;                                      // how the lux were gathered
    std::vector<ReportSurface> surfaces;
    std::vector<ReportObserver> observers;
    std::vector<ReportDaylightGlare> daylight_glare; // a daylight solution's observers
    std::vector<ReportView> views;
    const LuminaireSet* luminaires = nullptr; // none: no schedule, no glare
    double metres_per_unit = 1;
    double power_area_m2 = 0;             // the area the power density is over (0: not given)
    std::string power_area_what;          // which area that is, for the page
    std::optional<LightingEnergy> energy; // EN 15193-1's LENI, when asked for
    std::optional<RoomSummary> room;      // the room's size and surfaces
    // A daylight solution: the sky the factors are under, and the year's weather file (its
    // place) and occupied hours, when there is one.
    bool daylight = false;
    std::string daylight_sky, weather, occupancy;
    // Where north is (degrees from the scene's -Z towards +X, as rad-ff --north): a north
    // arrow on the horizontal plans; NaN: not known, no arrow.
    double north_deg = std::numeric_limits<double>::quiet_NaN();
    // Each small surface's values as a table under its plan (rad-report --point-tables).
    bool point_tables = false;
};

// Lux as the page shows it: three significant figures without an exponent (412, 41.2, 4.12;
// 1234 as 1234), "-" for NaN.
std::string lux_text(double lux);
// A ratio (U0, Emin/Emax) as the page shows it: two decimals.
std::string ratio_text(double ratio);
// The same beside a requirement (value >= required; NaN: none): with as many more decimals
// (up to four) as make the printed figure agree with its verdict (U0 0.5995 against 0.60 is
// "0.5995", never "0.60" beside "fails"; Em 499.6 against 500 is "499.6").
std::string lux_text(double lux, double required);
std::string ratio_text(double ratio, double required);

// The page.
std::string report_html(const ReportInput& input);

// Parts of the page (each its own file):
// a surface's false-colour plan of `values` (per sensor) with isolines labelled in `unit` and
// the luminaires above it, as SVG. `quantity` names what is drawn ("lux", "df", "da300": the
// isolines' group carries it); `top` is the colour scale's top (0: a round number at or over
// the largest value); `width` x `height` the room the surface is drawn in, px.
struct PlanScale {
    std::string quantity, unit;
    double top = 0;
    double width = 540, height = 400; // px the surface may take (the legend comes beside it)
    double north_deg = std::numeric_limits<double>::quiet_NaN(); // a north arrow (NaN: none)
};
std::string surface_plan_svg(const ReportSurface& surface, std::span<const double> values,
                             const PlanScale& scale, const LuminaireSet* luminaires,
                             double metres_per_unit);
// Whether a surface's plan is a reflected ceiling plan: it faces down (a ceiling), so the plan
// shows it from above, the same way round as the floor, not from the side its points face.
inline bool reflected_ceiling_plan(const SurfaceGrid& grid) {
    return grid.normal[1] < -0.9;
}
// Whether a surface is drawn as a plan (floor or ceiling: facing up or down), where its
// luminaires, the room's cut and north are drawn; a wall's elevation has none of them.
inline bool horizontal_plan(const SurfaceGrid& grid) {
    return std::abs(grid.normal[1]) >= 0.9;
}
// The key plan: the room's extent seen from above (x to the right, z down, as the floor's
// plans) with the calculation area (less its border band) of every surface facing up, named,
// and the luminaires as dots; SVG. Empty without the room.
std::string key_plan_svg(const ReportInput& input);
// A photometric file's polar curve (C0-C180 and C90-C270, cd/klm) as SVG, from `luminaire`'s
// frame.
std::string polar_curve_svg(const LuminaireSet& set, const Luminaire& luminaire);

// Text for HTML: & < > " escaped.
std::string html_escape(const std::string& text);

} // namespace rad
