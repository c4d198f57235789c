// rad-gather's daylight runs (see gather_daylight.hpp).
#include "gather_daylight.hpp"

#include "radiosity/melanopic.hpp"

#include "radfmt/chain.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/daylight_glare.hpp"
#include "radiosity/en17037.hpp"
#include "radiosity/error.hpp"
#include "radiosity/falsecolour.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/sensors.hpp"
#include "radiosity/shading.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/sunlight_exposure.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

namespace rad::tool {

namespace {
// --shaded and its rule, group and log: a window operated over the year.
void add_shading_options(CLI::App& app, DaylightArgs& a) {
    app.add_option("--shaded", a.shaded,
                   "With --annual: the window's shaded state (blinds down, a second glazing) as "
                   "MESH RADIOSITY: the same geometry with the window's material changed "
                   "(rad-mesh --transmittance), solved with its own .sky. Each hour takes the "
                   "state --shading-rule chooses; sDA is computed with the blinds as operated, "
                   "ASE with them up (IES LM-83-12), and the hours down are counted")
        ->expected(2);
    app.add_option("--shading-rule", a.shading_rule,
                   "With --shaded: lm83 (blinds down in any hour when more than 2% of the "
                   "sensors get 1000 lx or more of direct sun with them up), sun:LUX:PERCENT, "
                   "or schedule:FILE (one 0 or 1 a line for each hour of the weather file, 1: "
                   "down)")
        ->capture_default_str();
    app.add_option("--shading-group", a.shading_group,
                   "With --shaded and --surfaces: the sun rule watches this calculation "
                   "surface's sensors only (default: every sensor with a value)");
    app.add_option("--shading-log", a.shading_log,
                   "With --shaded: write the state of every hour as CSV (month,day,hour,"
                   "occupied,sunlit_share,shaded): the share of the watched sensors with the "
                   "rule's direct sun (1000 lx unless sun:LUX:...) with the blinds up, and 1 "
                   "where the shaded state was used");
}

// --glare and --sunlight-exposure: the eye's daylight and the sun's hours at points.
void add_glare_options(CLI::App& app, DaylightArgs& a) {
    app.add_option("--glare", a.glare,
                   "Daylight glare at an eye at x y z looking along dx dy dz (+Y up), \"x y z "
                   "dx dy dz\": the daylight glare probability (DGP, Wienold and "
                   "Christoffersen 2006, as Radiance's evalglare computes it from a fisheye "
                   "picture). With --sky: the vertical illuminance Ev and the glare sources, one "
                   "CSV line a view (x,y,z,dx,dy,dz,ev,dgp,sources,mean_luminance,low_light) on "
                   "-o. With --epw --annual: DGP at every occupied hour, the shares of them over "
                   "0.35, 0.40 and 0.45 and EN 17037's glare level, one CSV line a view "
                   "(x,y,z,dx,dy,dz,hours,over_035,over_040,over_045,mean_dgp,en17037) on -o "
                   "(repeatable)");
    app.add_option("--glare-hours", a.glare_hours,
                   "With --annual --glare: write every hour's DGP as CSV (month,day,hour,"
                   "occupied, then each view's dgp and ev; empty where not occupied)");
    app.add_option("--glare-threshold", a.glare_threshold,
                   "--glare: the luminance (cd/m^2) over which a direction belongs to a glare "
                   "source; at most 100: that times the view's mean luminance (evalglare -b)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e12));
    app.add_flag("--glare-no-low-light", a.glare_no_low_light,
                 "--glare: leave out DGP's low-light correction below 1000 lx of Ev");
    app.add_option("--sunlight-exposure", a.sunlight,
                   "EN 17037's sunlight exposure at a reference point inside a window, \"x y "
                   "z\": the minutes the sun reaches it (a straight ray toward the sun leaves "
                   "the scene, through glass) above --sun-min-altitude, each minute of --date's "
                   "day or, without it, of every day from 1 February to 21 March 2025; the best "
                   "day's hours and level (minimum 1.5 h, medium 3, high 4); one CSV line a point "
                   "(x,y,z,date,hours,level) on -o. The place: --location or --epw (repeatable)");
    app.add_option("--sun-min-altitude", a.sun_min_altitude,
                   "--sunlight-exposure: the sun counts from this altitude (degrees), EN "
                   "17037's minimum for the place's latitude (the standard's table)")
        ->check(CLI::Range(0.0, 90.0));
}
} // namespace

void add_daylight_options(CLI::App& app, DaylightArgs& a) {
    add_sky_options(app, a.choice,
                    "Daylight at an instant, from a solution solved with a .sky (rad-ff --sky, "
                    "rad-solve --direct); writes lux, one a line");
    app.add_flag("--daylight-factor", a.daylight_factor,
                 "With --sky (cie-overcast, as the standards define it): write the daylight "
                 "factor in % (the sensor's illuminance over the unobstructed sky's horizontal "
                 "illuminance), one a line, and its mean, median and share at 2% or more");
    app.add_option("--epw", a.epw,
                   "An EnergyPlus weather file: with --annual, a year of hourly Perez skies "
                   "and sun; with --date, the place");
    app.add_flag("--annual", a.annual,
                 "With --epw: every hour of the year at every sensor (the sky through daylight "
                 "coefficients, the sun's beam traced at the sensor) into -o FILE (.ill, "
                 "rad-info reads it), and LM-83's sDA300/50% and ASE1000,250h, DA300 and UDI "
                 "100-3000 lx over the occupied hours");
    app.add_option("--occupancy", a.occupancy,
                   "With --annual: the occupied hours, one 0 or 1 a line for each hour of the "
                   "weather file (default: 08:00 to 18:00 local standard time every day)");
    app.add_option("--metrics", a.metrics,
                   "With --annual: write each sensor's metrics as CSV (x,y,z,dx,dy,dz,da300,"
                   "udi_low,udi_useful,udi_high,sun_hours)");
    add_shading_options(app, a);
    add_glare_options(app, a);
    app.add_option("--sky-samples", a.sky_samples,
                   "Daylight: directions per sky patch a sensor traces (rounded to a square)")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000));
}

bool wants_daylight(const DaylightArgs& a) {
    return !a.choice.sky.empty() || a.annual || a.daylight_factor || !a.epw.empty() ||
           !a.glare.empty() || !a.sunlight.empty();
}

bool wants_glare(const DaylightArgs& a) {
    return !a.glare.empty() || !a.sunlight.empty();
}

namespace {

void check_daylight_args(const DaylightArgs& a, const DaylightRun& run) {
    if (a.annual == !a.choice.sky.empty()) {
        if (a.annual) throw InputError("--annual or --sky: a year or an instant, not both");
        throw InputError("daylight needs --sky SPEC (an instant) or --epw FILE --annual (a year)");
    }
    if (a.annual && a.epw.empty()) throw InputError("--annual needs --epw FILE");
    if (a.annual && a.glare.empty() && run.output.empty())
        throw InputError("--annual writes a binary .ill file: give -o FILE");
    if (a.daylight_factor && a.annual)
        throw InputError("--daylight-factor is for --sky cie-overcast, not --annual");
    if (!a.annual && (!a.occupancy.empty() || !a.metrics.empty()))
        throw InputError("--occupancy and --metrics go with --annual");
    const bool shading_options =
        a.shading_rule != "lm83" || !a.shading_group.empty() || !a.shading_log.empty();
    if (!a.annual && (!a.shaded.empty() || shading_options))
        throw InputError("--shaded and the --shading- options go with --annual");
    if (a.shaded.empty() && shading_options)
        throw InputError("--shading-rule, --shading-group and --shading-log are about when "
                         "--shaded's state is used: give --shaded MESH RADIOSITY");
    if (!a.shading_group.empty() && run.surfaces.empty())
        throw InputError("--shading-group names a calculation surface: give --surfaces FILE");
    if (!a.glare.empty() && a.daylight_factor)
        throw InputError("--glare gives DGP, not daylight factors: leave out --daylight-factor");
    if (!a.glare_hours.empty() && !(a.annual && !a.glare.empty()))
        throw InputError("--glare-hours goes with --annual --glare");
    if (!a.glare.empty() && a.annual && (!a.shaded.empty() || !a.metrics.empty()))
        throw InputError("--annual --glare gives DGP at views: not with --shaded or --metrics");
    if (a.annual && run.error && a.metrics.empty())
        throw InputError("--annual --error writes the metrics' errors beside them: give "
                         "--metrics FILE");
}

// "; 3 sensor(s) inside or behind objects: no value" (nothing when none).
std::string inside_text(std::size_t without) {
    if (without == 0) return "";
    return "; " + std::to_string(without) +
           " sensor(s) inside or behind objects: no value (nan), in no figure";
}

void write_png(const DaylightRun& run, const std::vector<double>& values, const std::string& unit,
               const std::string& title) {
    if (run.png.empty()) return;
    write_false_colour_png(run.png, values, run.grid_columns, run.grid_rows, unit, title,
                           run.lux_max);
}

// --surfaces: each surface's daylight factors' summary.
// " ± 0.012" of a mean's standard error (the values' in quadrature over their count).
std::string mean_error_text(std::span<const double> values, std::span<const double> errors) {
    return error_suffix(illuminance_errors(values, errors).mean);
}

void print_surface_factors(const DaylightRun& run, const std::vector<double>& values,
                           const std::vector<double>& errors) {
    std::size_t first = 0;
    for (const auto& [name, count] : run.surfaces) {
        const auto s = summarise_daylight_factors(std::vector<double>(
            values.begin() + long(first), values.begin() + long(first + count)));
        const auto error = mean_error_text(std::span(values).subspan(first, count),
                                           std::span(errors).subspan(first, count));
        std::fprintf(stderr,
                     "rad-gather: %s: daylight factor mean %.3g%%%s, median %.3g%%, min %.3g%%, "
                     "max %.3g%%; %.1f%% of its %zu sensor(s) at 2%% or more%s\n",
                     name.c_str(), s.mean, error.c_str(), s.median, s.min, s.max, 100 * s.above2,
                     s.counted, inside_text(s.without).c_str());
        first += count;
    }
}

// The sensors whose reflected light stopped at --max-rays before --accuracy: counted, the first
// few named.
void warn_sensors_at_budget(const DaylightRun& run,
                            const std::vector<DaylightSensors::Illuminance>& lux,
                            const std::vector<std::uint8_t>& inside) {
    long count = 0;
    std::string names;
    for (std::size_t k = 0; k < lux.size(); ++k) {
        if (!lux[k].at_budget || inside[k]) continue;
        if (count++ < 3)
            names += (names.empty() ? "" : ", ") +
                     (run.labels.empty() ? "sensor " + std::to_string(k) : run.labels[k]);
    }
    warn_at_budget("sensor(s)", count, std::max(run.max_rays, run.rays), run.accuracy, names);
}

// The sky's light at every sensor (NaN inside objects), scaled, with its error.
struct SensorValues {
    std::vector<double> values, errors;
};
SensorValues sensor_values(const DaylightRun& run, const DaylightSensors& sensors, const Sky& sky,
                           const std::vector<std::uint8_t>& inside, double scale,
                           std::vector<DaylightSensors::Illuminance>* raw = nullptr) {
    const auto lux = sensors.illuminance(sky, run.positions, run.normals, run.quiet);
    SensorValues out;
    for (std::size_t k = 0; k < lux.size(); ++k) {
        out.values.push_back(inside[k] ? std::nan("") : scale * lux[k].total());
        out.errors.push_back(inside[k] ? std::nan("") : scale * lux[k].error());
    }
    if (raw) *raw = lux;
    return out;
}

// --melanopic: the mean melanopic EDI over lux of the sensors with a value.
void print_melanopic_ratio(const SensorValues& lux, const SensorValues& melanopic,
                           const std::string& spectrum) {
    double e = 0, m = 0;
    for (std::size_t k = 0; k < lux.values.size(); ++k)
        if (std::isfinite(lux.values[k])) e += lux.values[k], m += melanopic.values[k];
    std::fprintf(stderr,
                 "rad-gather: melanopic: the sky's light as %s; melanopic EDI over lux at the "
                 "sensors: %.3f (the room's colours and glass; grey ones keep mel-DER)\n",
                 spectrum.c_str(), e > 0 ? m / e : 0.0);
}

// The sky's spectrum for --melanopic: D65, or the one --spectrum SPEC.
Spectrum sky_spectrum(const std::vector<std::string>& specs) {
    if (specs.empty()) return cie_d65();
    if (specs.size() > 1 || specs[0].find('=') != std::string::npos)
        throw InputError("--spectrum: a daylight solution's light is the sky's, one spectrum: "
                         "give --spectrum SPEC once (no GROUP=; the default is CIE D65)");
    return parse_spectrum(specs[0]);
}

int instant(const DaylightArgs& a, const DaylightRun& run, const DaylightSensors& sensors,
            const DaylightSensors* melanopic, const std::string& melanopic_source) {
    const auto sky = sky_of(a.choice, a.epw, sensors.frame());
    if (a.daylight_factor && sky.horizontal_illuminance() <= 0)
        throw InputError("--daylight-factor: the sky has no horizontal illuminance");
    const std::size_t n = run.positions.size();
    // A sensor inside furniture has no value (NaN), as in the lighting mode.
    const auto inside = sensors.inside(run.positions, run.normals);
    const double scale = a.daylight_factor ? 100 / sky.horizontal_illuminance() : 1;
    std::vector<DaylightSensors::Illuminance> lux;
    const auto [values, errors] = sensor_values(run, sensors, sky, inside, scale, &lux);
    const auto mel = melanopic ? sensor_values(run, *melanopic, sky, inside, 1) : SensorValues{};
    const auto without = static_cast<std::size_t>(std::count(inside.begin(), inside.end(), 1));
    warn_sensors_at_budget(run, lux, inside);
    write_output(run.output, [&](std::FILE* out) {
        if (!run.header_line.empty()) std::fprintf(out, "%s\n", run.header_line.c_str());
        if (run.labels.empty()) {
            for (std::size_t k = 0; k < n; ++k) {
                std::fprintf(out, run.error ? "%.6g %.3g" : "%.6g", values[k], errors[k]);
                if (melanopic)
                    std::fprintf(out, run.error ? " %.6g %.3g" : " %.6g", mel.values[k],
                                 mel.errors[k]);
                std::fputc('\n', out);
            }
            return;
        }
        const char* column = a.daylight_factor ? "df" : "lux";
        std::fprintf(out, "surface,index,column,row,x,y,z,%s", column);
        if (run.error) std::fprintf(out, ",%s_error", column);
        if (melanopic) std::fputs(run.error ? ",melanopic,melanopic_error" : ",melanopic", out);
        std::fputc('\n', out);
        for (std::size_t k = 0; k < n; ++k) {
            const auto& p = run.positions[k];
            std::fprintf(out, "%s,%.6g,%.6g,%.6g,%.6g", run.labels[k].c_str(), p[0], p[1], p[2],
                         values[k]);
            if (run.error) std::fprintf(out, ",%.3g", errors[k]);
            if (melanopic) std::fprintf(out, ",%.6g", mel.values[k]);
            if (melanopic && run.error) std::fprintf(out, ",%.3g", mel.errors[k]);
            std::fputc('\n', out);
        }
    });
    if (a.daylight_factor && !run.quiet) print_surface_factors(run, values, errors);
    if (a.daylight_factor) {
        write_png(run, values, "%", "daylight factor (%)");
        const auto s = summarise_daylight_factors(values);
        std::fprintf(stderr,
                     "rad-gather: daylight factor at %zu sensor(s) under the %s: mean %.3g%%%s, "
                     "median %.3g%%, min %.3g%%, max %.3g%%; %.1f%% of the sensors at 2%% or "
                     "more%s\n",
                     s.counted, sky.describe().c_str(), s.mean,
                     mean_error_text(values, errors).c_str(), s.median, s.min, s.max,
                     100 * s.above2, inside_text(without).c_str());
    } else {
        if (melanopic && !run.quiet)
            print_melanopic_ratio(SensorValues{values, errors}, mel, melanopic_source);
        write_png(run, values, "lux", "illuminance (lux) under the " + sky.describe());
        if (!run.quiet || without > 0)
            std::fprintf(stderr, "rad-gather: %s%s\n", sky.describe().c_str(),
                         inside_text(without).c_str());
    }
    return 0;
}

void write_metrics_csv(const std::string& path, const radfmt::AnnualData& year,
                       const AnnualMetrics& m, const std::vector<std::string>& labels,
                       const AnnualErrors* errors) {
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp);
        if (!labels.empty()) out << "surface,index,column,row,";
        out << "x,y,z,dx,dy,dz,da300,udi_low,udi_useful,udi_high,sun_hours";
        out << (errors ? ",da300_error,udi_useful_error\n" : "\n");
        char line[256];
        for (std::size_t k = 0; k < year.sensors(); ++k) {
            if (!labels.empty()) out << labels[k] << ',';
            const auto& p = year.positions[k];
            const auto& d = year.normals[k];
            const auto& s = m.sensors[k];
            std::snprintf(line, sizeof line, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f,%.4f,%.4f,%d",
                          p[0], p[1], p[2], d[0], d[1], d[2], s.da300, s.udi_low, s.udi_useful,
                          s.udi_high, s.sun_hours);
            out << line;
            if (errors) {
                std::snprintf(line, sizeof line, ",%.2g,%.2g", errors->da300[k],
                              errors->udi_useful[k]);
                out << line;
            }
            out << '\n';
        }
        if (!out.flush()) throw SystemError(path + ": cannot write");
    });
}

// " ± 0.3" (a share's standard error in percentage points), or " ± ?" when not known.
std::string percent_error(double error) {
    if (!std::isfinite(error)) return " ± ?";
    char text[32];
    std::snprintf(text, sizeof text, " ± %.2g", 100 * error);
    return text;
}

// The window's shaded state (--shaded MESH RADIOSITY), read and checked against the open
// state's geometry.
struct ShadedState {
    radfmt::MeshData mesh;
    radfmt::RadiosityData solution;
    radfmt::Header rad_header;
};

ShadedState read_shaded_state(const DaylightArgs& a, const DaylightRun& run) {
    ShadedState s;
    const auto& mesh_path = a.shaded[0];
    const auto& rad_path = a.shaded[1];
    s.mesh = radfmt::read_mesh(mesh_path);
    s.solution = radfmt::read_radiosity(rad_path, &s.rad_header);
    radfmt::require_same_geometry(rad_path, s.rad_header, s.solution.radiosity.size(), mesh_path,
                                  s.mesh, "run rad-ff and rad-solve on " + mesh_path + " again");
    apply_recorded_overrides(s.mesh, s.rad_header);
    if (s.mesh.vertices != run.mesh->vertices || s.mesh.patches.size() != run.mesh->patches.size())
        throw InputError(mesh_path + ": --shaded's mesh is not the geometry of " + run.inputs[0] +
                         " (" + std::to_string(s.mesh.patches.size()) + " patches against " +
                         std::to_string(run.mesh->patches.size()) +
                         "): make both states with rad-mesh from the same scene and options, "
                         "changing only the window's material (--transmittance)");
    return s;
}

// The sensors the sun rule watches: those with a value, of --shading-group's surface if given.
std::vector<std::uint8_t> judged_sensors(const DaylightArgs& a, const DaylightRun& run,
                                         const std::vector<std::uint8_t>& inside) {
    std::vector<std::uint8_t> judged(inside.size());
    for (std::size_t k = 0; k < inside.size(); ++k) judged[k] = !inside[k];
    if (a.shading_group.empty()) return judged;
    std::size_t first = 0;
    bool found = false;
    std::string names;
    for (const auto& [name, count] : run.surfaces) {
        const bool group = name == a.shading_group;
        found = found || group;
        names += (names.empty() ? "" : ", ") + name;
        for (std::size_t k = first; k < first + count; ++k) judged[k] = judged[k] && group;
        first += count;
    }
    if (!found)
        throw InputError("--shading-group '" + a.shading_group +
                         "': no calculation surface of that name (the surfaces: " + names + ")");
    return judged;
}

// The year with the window operated (--shaded), by --shading-rule.
OperatedYear operated(const DaylightArgs& a, const DaylightRun& run,
                      const DaylightSensors& open_sensors, const Weather& weather,
                      const std::vector<std::uint8_t>& occupied,
                      const std::vector<std::uint8_t>& inside, std::vector<std::string>& notes,
                      AnnualReplicates* replicates) {
    const auto rule = parse_shading_rule(a.shading_rule, weather.hours.size());
    const auto judged = judged_sensors(a, run, inside);
    const auto state = read_shaded_state(a, run);
    const DaylightSensors closed_sensors(
        state.mesh, daylight_solution(state.solution, state.rad_header, a.shaded[1]),
        daylight_options(a.sky_samples, run.rays, run.seed, run.accuracy, run.max_rays));
    return operated_annual(open_sensors, closed_sensors, run.positions, run.normals, weather,
                           occupied, a.choice.ground, rule, judged, inside, run.quiet, &notes,
                           replicates);
}

void write_shading_log(const std::string& path, const OperatedYear& s) {
    const auto& year = s.year;
    write_output(path, [&](std::FILE* out) {
        std::fprintf(out, "month,day,hour,occupied,sunlit_share,shaded\n");
        for (std::size_t t = 0; t < year.hours.size(); ++t) {
            const auto h = year.hours[t];
            std::fprintf(out, "%u,%u,%u,%d,%.6g,%d\n", h / 10000, h / 100 % 100, h % 100,
                         int(year.occupied[t]), s.sunlit[t], int(s.down[t]));
        }
    });
}

void print_shading(const DaylightArgs& a, const OperatedYear& s, int occupied_hours) {
    std::printf("  blinds down    %6.1f %% of occupied hours (%d of %d): %s, the shaded state %s\n",
                occupied_hours ? 100.0 * s.occupied_down / occupied_hours : 0.0, s.occupied_down,
                occupied_hours, s.rule.c_str(), a.shaded[1].c_str());
}

// EN 17037's illuminance method on the sensors `plane` marks: one line.
void print_en17037(const std::string& what, const radfmt::AnnualData& year,
                   const std::vector<std::uint8_t>& plane,
                   const std::vector<std::uint8_t>& daylight_hours) {
    const auto e = en17037_illuminance_method(year, plane, daylight_hours);
    if (e.points == 0) return;
    std::printf("  %sEN 17037 by illuminance, over %d daylight hours: ", what.c_str(),
                e.daylight_hours);
    for (const auto& l : e.levels)
        std::printf("%s (%g lx over 50%% in %.1f%%, %g lx over 95%% in %.1f%% of them) %s; ",
                    l.name, l.target_lux, 100 * l.target_hours, l.minimum_lux,
                    100 * l.minimum_hours, l.met ? "met" : "not met");
    std::printf("level %s\n", e.achieved().c_str());
}

// EN 17037 by illuminance: the whole set of sensors (a --grid, --points), or each work plane
// of --surfaces.
void print_en17037_planes(const DaylightRun& run, const radfmt::AnnualData& year,
                          const std::vector<std::uint8_t>& inside, const Weather& weather) {
    const auto hours = en17037_daylight_hours(weather);
    const std::size_t n = year.sensors();
    if (run.surfaces.empty()) {
        std::vector<std::uint8_t> plane(n);
        for (std::size_t k = 0; k < n; ++k) plane[k] = !inside[k];
        print_en17037("", year, plane, hours);
        return;
    }
    std::size_t first = 0;
    for (std::size_t s = 0; s < run.surfaces.size(); ++s) {
        const auto& [name, count] = run.surfaces[s];
        if (run.reference_planes[s]) {
            std::vector<std::uint8_t> plane(n, 0);
            for (std::size_t k = first; k < first + count; ++k) plane[k] = !inside[k];
            print_en17037(name + ": ", year, plane, hours);
        }
        first += count;
    }
}

// The .ill's header: provenance, the place, the occupancy, and the shading when operated.
radfmt::Header annual_header(const DaylightArgs& a, const DaylightRun& run, const Weather& weather,
                             const OperatedYear* shading) {
    std::vector<radfmt::Parent> parents;
    for (const auto& i : run.inputs) parents.push_back({i, nullptr});
    auto header = radfmt::derived_header(tool_version("rad-gather"), run.command, parents);
    header.set("place", weather.place);
    header.set("occupancy", a.occupancy.empty() ? "08:00-18:00 every day" : a.occupancy);
    if (shading) {
        header.set("shading", shading->rule + "; shaded state " + a.shaded[1] +
                                  "; direct sun (sun_lux) with the blinds up");
        header.set("hours_shaded", std::to_string(shading->occupied_down));
    }
    return header;
}

// The year's figures on standard output: sDA, ASE, DA300, UDI (with their errors under
// --error), and the blinds' hours when operated.
void print_year_summary(const DaylightArgs& a, const DaylightRun& run, const Weather& weather,
                        const AnnualMetrics& m, const AnnualErrors& errors,
                        const OperatedYear* shading, std::size_t without) {
    std::printf("annual daylight at %zu sensor(s), %s (%.2f N, %.2f E), %d occupied hour(s) "
                "(%s)%s:\n",
                m.counted, weather.place.c_str(), weather.location.latitude,
                weather.location.longitude, m.occupied_hours, occupancy_text(a.occupancy).c_str(),
                inside_text(without).c_str());
    if (shading) print_shading(a, *shading, m.occupied_hours);
    const auto pm = [&](double error) { return run.error ? percent_error(error) : std::string(); };
    std::printf("  sDA300/50%%     %6.1f %%%s of sensors (DA300 >= 50%%)", 100 * m.sda,
                pm(errors.sda).c_str());
    if (shading)
        std::printf(", blinds as operated (%.1f %% with them up all year)",
                    100 * shading->open.sda);
    std::printf("\n  ASE1000,250h   %6.1f %%%s of sensors (direct sun >= 1000 lx for > 250 h)%s\n",
                100 * m.ase, run.error ? " ± 0 (the sun's beam, exact)" : "",
                shading ? ", blinds up (as LM-83 computes it)" : "");
    std::printf("  DA300 mean     %6.1f %%%s of occupied hours\n", 100 * m.da300,
                pm(errors.da300_mean).c_str());
    std::printf("  UDI 100-3000   %6.1f %%%s of occupied hours (mean)\n", 100 * m.udi_useful,
                pm(errors.udi_useful_mean).c_str());
}

int annual(const DaylightArgs& a, const DaylightRun& run, const DaylightSensors& sensors) {
    const auto weather = read_epw(a.epw);
    if (weather.missing > 0)
        std::fprintf(stderr, "rad-gather: %s: %d hour(s) with missing radiation, taken as 0\n",
                     a.epw.c_str(), weather.missing);
    const auto occupied = occupied_hours(a.occupancy, weather);
    const auto inside = sensors.inside(run.positions, run.normals);
    std::vector<std::string> notes;
    AnnualReplicates replicates;
    std::optional<OperatedYear> shading;
    radfmt::AnnualData plain;
    if (a.shaded.empty())
        plain = annual_illuminance(sensors, run.positions, run.normals, weather, occupied,
                                   a.choice.ground, run.quiet, &notes,
                                   run.error ? &replicates : nullptr);
    else
        shading = operated(a, run, sensors, weather, occupied, inside, notes,
                           run.error ? &replicates : nullptr);
    const auto& year = shading ? shading->year : plain;
    for (const auto& note : notes) std::fprintf(stderr, "rad-gather: %s\n", note.c_str());
    const auto header = annual_header(a, run, weather, shading ? &*shading : nullptr);
    radfmt::write_annual(run.output, header, year);
    if (shading && !a.shading_log.empty()) write_shading_log(a.shading_log, *shading);
    const auto m = annual_metrics(year, inside);
    const auto errors = annual_errors(replicates, m);
    if (!a.metrics.empty())
        write_metrics_csv(a.metrics, year, m, run.labels, run.error ? &errors : nullptr);
    if (!run.png.empty()) {
        std::vector<double> da;
        for (const auto& s : m.sensors) da.push_back(100 * s.da300);
        write_false_colour_png(run.png, da, run.grid_columns, run.grid_rows, "%",
                               "DA300: % of hours at 300 lx or more", 100);
    }
    print_year_summary(a, run, weather, m, errors, shading ? &*shading : nullptr,
                       year.sensors() - m.counted);
    print_en17037_planes(run, year, inside, weather);
    const auto pm = [&](double error) { return run.error ? percent_error(error) : std::string(); };
    std::size_t first = 0;
    for (const auto& [name, count] : run.surfaces) { // --surfaces: each surface's figures
        const auto part = summarise_sensor_metrics(
            {m.sensors.begin() + long(first), m.sensors.begin() + long(first + count)},
            m.occupied_hours);
        const auto e = annual_errors(replicates, part, first);
        std::printf("  %s: sDA300/50%% %.1f %%%s, ASE1000,250h %.1f %%, DA300 mean %.1f %%%s, UDI "
                    "100-3000 %.1f %%%s\n",
                    name.c_str(), 100 * part.sda, pm(e.sda).c_str(), 100 * part.ase,
                    100 * part.da300, pm(e.da300_mean).c_str(), 100 * part.udi_useful,
                    pm(e.udi_useful_mean).c_str());
        first += count;
    }
    return 0;
}
} // namespace

namespace {
// "x y z dx dy dz" of --glare.
std::pair<Vec3, Vec3> glare_view(const std::string& text) {
    std::istringstream in(text);
    Vec3 eye{}, view{};
    if (!(in >> eye[0] >> eye[1] >> eye[2] >> view[0] >> view[1] >> view[2]) ||
        !(in >> std::ws).eof())
        throw InputError("--glare '" + text +
                         "': give the eye and the direction it looks, \"x y z dx dy dz\"");
    for (const double v : {eye[0], eye[1], eye[2], view[0], view[1], view[2]})
        if (!std::isfinite(v)) throw InputError("--glare '" + text + "': a number is not finite");
    if (length(view) == 0) throw InputError("--glare '" + text + "': the direction is zero");
    return {eye, normalized(view)};
}

void print_glare(const std::string& text, const DaylightGlare& g) {
    std::fprintf(
        stderr,
        "rad-gather: glare at %s: DGP %.3f, Ev %.0f lx, %zu glare source(s) over %.0f "
        "cd/m^2, mean luminance %.0f cd/m^2%s\n",
        text.c_str(), g.dgp, g.ev, g.sources.size(), g.threshold, g.mean_luminance,
        g.low_light < 1 ? (", low-light correction x" + std::to_string(g.low_light)).c_str() : "");
    for (const auto& s : g.sources)
        std::fprintf(stderr,
                     "  %s: %.4g cd/m^2 over %.3g sr, %.1f deg from the line of sight (tau %.0f "
                     "deg), position index %.2f\n",
                     s.sun ? "the sun" : "source", s.luminance, s.solid_angle, s.sigma_deg,
                     s.tau_deg, s.position_index);
}

void write_glare_hours(const std::string& path, const Weather& weather,
                       const std::vector<std::uint8_t>& occupied,
                       const std::vector<std::vector<DaylightGlare>>& views) {
    write_output(path, [&](std::FILE* out) {
        std::fprintf(out, "month,day,hour,occupied");
        for (std::size_t v = 0; v < views.size(); ++v)
            std::fprintf(out, ",dgp%zu,ev%zu", v + 1, v + 1);
        std::fputc('\n', out);
        for (std::size_t t = 0; t < weather.hours.size(); ++t) {
            const auto& h = weather.hours[t];
            std::fprintf(out, "%d,%d,%d,%d", h.month, h.day, h.hour, int(occupied[t]));
            for (const auto& view : views) {
                if (std::isfinite(view[t].dgp))
                    std::fprintf(out, ",%.4f,%.6g", view[t].dgp, view[t].ev);
                else
                    std::fputs(",,", out);
            }
            std::fputc('\n', out);
        }
    });
}

int annual_glare(const DaylightArgs& a, const DaylightRun& run, const DaylightLuminance& luminance,
                 const std::vector<std::pair<Vec3, Vec3>>& views, GlareOptions options) {
    const auto weather = read_epw(a.epw);
    const auto occupied = occupied_hours(a.occupancy, weather);
    const auto solution = daylight_solution(*run.solution, *run.rad_header, run.rad_path);
    const auto skies = hourly_skies(weather, solution.patches, solution.frame, a.choice.ground);
    options.rings = kAnnualGlareRings;
    std::vector<std::vector<DaylightGlare>> hours;
    for (const auto& [eye, view] : views)
        hours.push_back(luminance.annual_glare(skies, occupied, eye, view, options));
    if (!a.glare_hours.empty()) write_glare_hours(a.glare_hours, weather, occupied, hours);
    std::vector<GlareYear> years;
    for (const auto& h : hours) years.push_back(summarise_glare_year(h));
    write_output(run.output, [&](std::FILE* out) {
        if (!run.header_line.empty()) std::fprintf(out, "%s\n", run.header_line.c_str());
        std::fprintf(out, "x,y,z,dx,dy,dz,hours,over_035,over_040,over_045,mean_dgp,en17037\n");
        for (std::size_t k = 0; k < views.size(); ++k) {
            const auto& [eye, view] = views[k];
            const auto& y = years[k];
            std::fprintf(out, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.4f,%.4f,%.4f,%.4f,%s\n", eye[0],
                         eye[1], eye[2], view[0], view[1], view[2], y.hours, y.over_035, y.over_040,
                         y.over_045, y.mean, y.en17037());
        }
    });
    if (!run.quiet)
        for (std::size_t k = 0; k < views.size(); ++k) {
            const auto& y = years[k];
            std::fprintf(stderr,
                         "rad-gather: glare at %s over %d occupied hour(s), %s: DGP over 0.35 in "
                         "%.1f%%, over 0.40 in %.1f%%, over 0.45 in %.1f%% of them (mean %.3f); "
                         "EN 17037's protection from glare: %s\n",
                         a.glare[k].c_str(), y.hours, weather.place.c_str(), 100 * y.over_035,
                         100 * y.over_040, 100 * y.over_045, y.mean, y.en17037());
        }
    return 0;
}

int glare(const DaylightArgs& a, const DaylightRun& run) {
    if (a.choice.sky.empty() && !a.annual)
        throw InputError("--glare needs a sky: --sky SPEC (with --sun or --date for the sun), or "
                         "a year: --epw FILE --annual");
    GlareOptions options;
    options.threshold = a.glare_threshold;
    options.low_light = !a.glare_no_low_light;
    std::vector<std::pair<Vec3, Vec3>> views;
    for (const auto& text : a.glare) views.push_back(glare_view(text));
    const auto view_file =
        solution_sky_view(*run.rad_header, run.rad_path, run.direct_path, *run.mesh, run.inputs[0]);
    const DaylightLuminance luminance(
        *run.mesh, daylight_solution(*run.solution, *run.rad_header, run.rad_path), view_file);
    if (a.annual) return annual_glare(a, run, luminance, views, options);
    const auto sky = sky_of(a.choice, a.epw, daylight_frame(*run.rad_header, run.rad_path));
    if (!run.quiet) std::fprintf(stderr, "rad-gather: %s\n", sky.describe().c_str());
    std::vector<DaylightGlare> results;
    for (const auto& [eye, view] : views)
        results.push_back(luminance.glare(sky, eye, view, options));
    write_output(run.output, [&](std::FILE* out) {
        if (!run.header_line.empty()) std::fprintf(out, "%s\n", run.header_line.c_str());
        std::fprintf(out, "x,y,z,dx,dy,dz,ev,dgp,sources,mean_luminance,low_light\n");
        for (std::size_t k = 0; k < views.size(); ++k) {
            const auto& [eye, view] = views[k];
            const auto& g = results[k];
            std::fprintf(out, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.4f,%zu,%.6g,%.4f\n", eye[0],
                         eye[1], eye[2], view[0], view[1], view[2], g.ev, g.dgp, g.sources.size(),
                         g.mean_luminance, g.low_light);
        }
    });
    if (!run.quiet)
        for (std::size_t k = 0; k < views.size(); ++k) print_glare(a.glare[k], results[k]);
    return 0;
}
} // namespace

namespace {
// "x y z" of --sunlight-exposure.
Vec3 sunlight_point(const std::string& text) {
    std::istringstream in(text);
    Vec3 p{};
    if (!(in >> p[0] >> p[1] >> p[2]) || !(in >> std::ws).eof() || !std::isfinite(p[0]) ||
        !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw InputError("--sunlight-exposure '" + text +
                         "': give the reference point, \"x y z\" (finite numbers)");
    return p;
}

std::string date_text(const LocalTime& d) {
    char text[16];
    std::snprintf(text, sizeof text, "%04d-%02d-%02d", d.year, d.month, d.day);
    return text;
}

int sunlight_exposure(const DaylightArgs& a, const DaylightRun& run) {
    if (!a.choice.sky.empty() || a.annual || !a.glare.empty() || a.daylight_factor)
        throw InputError("--sunlight-exposure counts the sun's minutes itself: not with --sky, "
                         "--annual, --glare or --daylight-factor");
    if (!std::isfinite(a.sun_min_altitude))
        throw InputError("--sunlight-exposure needs --sun-min-altitude DEG: EN 17037's minimum "
                         "solar altitude for the place's latitude (the standard's table)");
    if (!a.choice.time.empty() || !a.choice.sun.empty())
        throw InputError("--sunlight-exposure takes a day (--date), not --time or --sun");
    Location where;
    if (!a.choice.location.empty())
        where = parse_location(a.choice.location);
    else if (!a.epw.empty())
        where = read_epw(a.epw).location;
    else
        throw InputError("--sunlight-exposure needs the place: --location LAT,LON,TZ or --epw");
    const auto days = a.choice.date.empty()
                          ? en17037_sunlight_days(2025)
                          : std::vector<LocalTime>{parse_local_time(a.choice.date, "12:00")};
    const SkyFrame frame = is_daylight_solution(*run.rad_header)
                               ? daylight_frame(*run.rad_header, run.rad_path)
                               : SkyFrame{};
    const SunlightScene scene(*run.mesh);
    std::vector<Vec3> points;
    for (const auto& text : a.sunlight) points.push_back(sunlight_point(text));
    std::vector<SunlightExposure> results;
    for (const auto& p : points)
        results.push_back(scene.exposure(p, where, frame, days, a.sun_min_altitude));
    write_output(run.output, [&](std::FILE* out) {
        if (!run.header_line.empty()) std::fprintf(out, "%s\n", run.header_line.c_str());
        std::fprintf(out, "x,y,z,date,hours,level\n");
        for (std::size_t k = 0; k < results.size(); ++k) {
            const auto& p = points[k];
            std::fprintf(out, "%.6g,%.6g,%.6g,%s,%.4f,%s\n", p[0], p[1], p[2],
                         date_text(results[k].best.date).c_str(), results[k].best.hours(),
                         results[k].level());
        }
    });
    if (!run.quiet)
        for (std::size_t k = 0; k < results.size(); ++k)
            std::fprintf(stderr,
                         "rad-gather: sunlight exposure at %s: %.2f h on %s (%zu day(s), the sun "
                         "counted from %g deg): EN 17037 level %s\n",
                         a.sunlight[k].c_str(), results[k].best.hours(),
                         date_text(results[k].best.date).c_str(), results[k].days.size(),
                         a.sun_min_altitude, results[k].level());
    return 0;
}
} // namespace

DaylightOptions daylight_options(int sky_samples, int rays, std::uint64_t seed, double accuracy,
                                 int max_rays) {
    DaylightOptions options;
    options.accuracy = accuracy;
    options.max_rays = max_rays;
    options.sky_side = std::max(1, int(std::lround(std::sqrt(double(sky_samples)))));
    options.rays = rays; // 0: no reflected light
    options.seed = seed;
    return options;
}

std::vector<std::uint8_t> occupied_hours(const std::string& occupancy, const Weather& weather) {
    return occupancy.empty() ? default_occupancy(weather)
                             : read_occupancy(occupancy, weather.hours.size());
}

std::string occupancy_text(const std::string& occupancy) {
    return occupancy.empty() ? "08:00-18:00 local standard time, every day" : occupancy;
}

int gather_daylight(const DaylightArgs& a, const DaylightRun& run) {
    if (!a.sunlight.empty()) return sunlight_exposure(a, run);
    check_daylight_args(a, run);
    if (!a.glare.empty()) return glare(a, run);
    const DaylightSensors sensors(
        *run.mesh, daylight_solution(*run.solution, *run.rad_header, run.rad_path),
        daylight_options(a.sky_samples, run.rays, run.seed, run.accuracy, run.max_rays));
    if (a.annual) return annual(a, run, sensors);
    if (!run.melanopic) return instant(a, run, sensors, nullptr, "");
    if (a.daylight_factor)
        throw InputError("--melanopic gives melanopic EDI (lx) under a sky (--sky), not a "
                         "daylight factor");
    const auto spectrum = sky_spectrum(run.spectra);
    const DaylightSensors melanopic(
        *run.mesh, daylight_solution(*run.solution, *run.rad_header, run.rad_path),
        melanopic_daylight_options(
            daylight_options(a.sky_samples, run.rays, run.seed, run.accuracy, run.max_rays),
            spectrum));
    char text[160];
    std::snprintf(text, sizeof text, "%s (mel-DER %.4f)", spectrum.name.c_str(),
                  melanopic_der(spectrum));
    return instant(a, run, sensors, &melanopic, text);
}

} // namespace rad::tool
