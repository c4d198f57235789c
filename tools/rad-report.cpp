// rad-report: mesh + solution + calculation surfaces -> a lighting report (HTML, and PDF).
#include "gather_daylight.hpp"
#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/gathered.hpp"
#include "radiosity/glare.hpp"
#include "radiosity/image_io.hpp"
#include "radiosity/luminaire_image.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/report.hpp"
#include "radiosity/report_pdf.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/version.hpp"
#include "radiosity/view.hpp"
#include "radiosity/weather.hpp"
#include "tool.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <numbers>

namespace {

struct ReportArgs {
    std::vector<std::string> inputs;
    std::string surfaces, output, pdf, project, date, direct, smooth = "crease";
    std::string epw, occupancy, energy, client, designer;
    double ground = 0.2;
    int sky_samples = 64;
    CLI::Option* rays_option = nullptr;
    rad::GatherOptions options;
    double area = 0;
    double north = std::numeric_limits<double>::quiet_NaN();
    int threads = 0;
    bool quiet = false, point_tables = false;
};

void add_options(CLI::App& app, ReportArgs& a) {
    app.add_option("MESH RADIOSITY", a.inputs,
                   "Patch mesh from rad-mesh and radiosity from "
                   "rad-solve for it")
        ->required()
        ->expected(2);
    app.add_option("--surfaces", a.surfaces,
                   "The calculation surfaces and observers (CSV; formats/README.md, "
                   "\"Calculation surfaces\"): rad-gather --surfaces reads the same file")
        ->required();
    app.add_option("-o,--output", a.output, "Write the report's page (HTML) here")->required();
    app.add_option("--pdf", a.pdf,
                   "Also print the page to this PDF (A4) with headless Chromium ($RAD_CHROMIUM "
                   "or chromium on PATH)");
    app.add_option("--project", a.project,
                   "The project's name on the title block (default: "
                   "the mesh file's name)");
    app.add_option("--client", a.client, "The client's name on the title block");
    app.add_option("--designer", a.designer,
                   "The designer's name (and firm) on the title block, who signs the report");
    app.add_option("--date", a.date, "The date on the title block (default: today, YYYY-MM-DD)");
    app.add_option("--direct", a.direct,
                   "The luminaires file (.lum) the solution was solved with, when it has moved "
                   "(default: the one rad-solve --direct recorded)");
    app.add_option("--area", a.area,
                   "The floor area (m^2) the installed power density is over (default: the "
                   "largest floor or work plane's whole rectangle)")
        ->check(rad::tool::finite_range(1e-9, 1e12));
    app.add_option("--energy", a.energy,
                   "Also the lighting energy (LENI) by EN 15193-1's quick method: a building "
                   "type (office, education, hospital, hotel, restaurant, sports, retail, "
                   "manufacturing) for its operating hours, then any of tD, tN (hours), FC, FO, FD "
                   "(dependency factors, default 1), Ppc, Pem (standby and emergency charging W, "
                   "default 0), te (charging hours, default 8760) as KEY=VALUE, e.g. "
                   "office,FO=0.9,Pem=6");
    app.add_option("--epw", a.epw,
                   "A daylight solution: also the year's metrics (sDA300/50%, ASE1000,250h, "
                   "DA300, UDI) and DA300 plans from this weather file, as rad-gather --epw "
                   "--annual");
    app.add_option("--occupancy", a.occupancy,
                   "With --epw: the occupied hours, one 0 or 1 a line (default 08:00-18:00 "
                   "local standard time, every day)");
    app.add_option("--ground", a.ground, "A daylight solution: the ground's reflectance")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1));
    app.add_option("--north", a.north,
                   "Where north is, in degrees from the scene's -Z axis towards +X (clockwise "
                   "seen from above, as rad-ff --north): a north arrow on the horizontal plans "
                   "(default: a daylight solution's own north; none for luminaires alone)")
        ->check(rad::tool::finite_range(-360, 360));
    app.add_flag("--point-tables", a.point_tables,
                 "Under each plan, its points' values as a table laid out as the plan (grids "
                 "of up to 20 columns and 400 points; larger ones say they were left out)");
    app.add_option("--sky-samples", a.sky_samples,
                   "A daylight solution: directions per sky patch a sensor traces (as rad-gather)")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000));
    a.rays_option = rad::tool::add_sensor_gather_options(
        app, a.options, a.smooth, "; daylight: 1024 unless given; as rad-gather");
    rad::tool::add_common_options(app, {.threads = &a.threads,
                                        .seed = &a.options.seed,
                                        .seed_help = "each sensor's own random stream (seed, "
                                                     "sensor index; as rad-gather)",
                                        .quiet = &a.quiet,
                                        .shows_progress = true});
}

std::string today() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[16];
    std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
    return text;
}

// The surfaces' grids and lux, their figures and verdicts.
std::vector<rad::ReportSurface> surfaces_of(const rad::CalcFile& file,
                                            const rad::Gatherer& gatherer,
                                            const rad::LuminaireSet* luminaires,
                                            const rad::Box& box, double metres_per_unit,
                                            bool quiet) {
    const auto grids = rad::surface_grids(file, metres_per_unit);
    auto gathered = rad::gather_surfaces(
        gatherer, luminaires, box, grids, quiet, [&](const rad::SensorsEstimate& e) {
            if (!quiet) rad::tool::say_sensors_estimate("rad-report", e, false);
            return true;
        });
    std::vector<rad::ReportSurface> out;
    for (std::size_t k = 0; k < grids.size(); ++k) {
        rad::ReportSurface s;
        s.surface = file.surfaces[k];
        s.grid = grids[k];
        s.lux = std::move(gathered[k].lux);
        s.lux_error = std::move(gathered[k].error);
        s.horizontal = std::move(gathered[k].horizontal);
        s.at_budget = std::move(gathered[k].at_budget);
        s.facing_distance_m = gathered[k].facing_distance_m;
        if (!quiet) rad::tool::warn_facing_too_close("rad-report", s.surface, s.facing_distance_m);
        s.stats = rad::illuminance_stats(s.lux);
        s.errors = rad::illuminance_errors(s.lux, s.lux_error);
        s.verdict = rad::judge(s.stats, s.surface.required, s.errors);
        out.push_back(std::move(s));
    }
    return out;
}

// Each observer's background luminance (the surfaces' light at the eye, over pi) and glare.
std::vector<rad::ReportObserver> observers_of(const rad::CalcFile& file,
                                              const rad::Gatherer& gatherer,
                                              const rad::LuminaireSet* luminaires,
                                              const rad::Box& box, std::uint64_t first_index) {
    std::vector<rad::ReportObserver> out;
    if (!file.observers.empty() && !luminaires)
        throw rad::InputError(file.name + ": observers' glare (UGR) is from luminaires, and the "
                                          "solution has none (rad-ff --luminaires, rad-solve "
                                          "--direct): remove the observer lines");
    for (std::size_t k = 0; k < file.observers.size(); ++k) {
        const auto& o = file.observers[k];
        std::string problem;
        const auto at_eye = rad::gather_sensor(gatherer, nullptr, box, o.position, o.view,
                                               first_index + k, problem);
        if (!problem.empty()) throw rad::InputError(o.where, "the observer's eye: " + problem);
        rad::ReportObserver r{o, 0, {}};
        r.background = rad::lux(at_eye.total()) / std::numbers::pi;
        r.glare =
            rad::observer_glare(*luminaires, &gatherer.scene(), o.position, o.view, r.background);
        out.push_back(std::move(r));
    }
    return out;
}

// The area the power density is over: --area, or the largest floor or work plane.
void power_area(const ReportArgs& a, const rad::CalcFile& file, double metres_per_unit,
                rad::ReportInput& in) {
    if (a.area > 0) {
        in.power_area_m2 = a.area;
        in.power_area_what = "the floor area given";
        return;
    }
    for (const auto& s : file.surfaces) {
        if (s.kind != rad::CalcKind::Floor && s.kind != rad::CalcKind::WorkPlane) continue;
        const double area = rad::length(s.u) * rad::length(s.v) * metres_per_unit * metres_per_unit;
        if (area > in.power_area_m2) {
            in.power_area_m2 = area;
            in.power_area_what = "the whole rectangle of '" + s.name + "'";
        }
    }
}

std::string method_text(const ReportArgs& a, const radfmt::Header& rad_header, bool luminaires) {
    const auto* method = rad_header.find("method");
    char text[700];
    std::snprintf(text, sizeof text,
                  "Illuminance at each point by a final gather over the radiosity solution "
                  "(solver %s): the light of the room's surfaces from %s%s, %s%d shadow rays "
                  "for emitting and bright surfaces, seed %llu.",
                  method ? method->c_str() : "?",
                  a.options.exact
                      ? "the exact sum over every patch"
                      : (std::to_string(a.options.rays) + " cosine-weighted rays").c_str(),
                  a.options.exact ? "" : " per point",
                  luminaires ? "the luminaires' direct light exactly from their photometric "
                               "files with a visibility ray per point (the luminous opening "
                               "sampled where near), "
                             : "",
                  a.options.shadow_rays, static_cast<unsigned long long>(a.options.seed));
    return text;
}

// A daylight solution's observers: DGP at every occupied hour, as rad-gather --annual --glare.
std::vector<rad::ReportDaylightGlare>
observers_daylight_glare(const ReportArgs& a, const rad::CalcFile& file,
                         const radfmt::MeshData& mesh, const radfmt::RadiosityData& solution,
                         const radfmt::Header& rad_header, const rad::HourlySkies& skies,
                         const std::vector<std::uint8_t>& occupied) {
    const auto view = rad::solution_sky_view(rad_header, a.inputs[1], "", mesh, a.inputs[0]);
    const auto daylight = rad::daylight_solution(solution, rad_header, a.inputs[1]);
    const rad::DaylightLuminance luminance(mesh, daylight, view);
    rad::GlareOptions options;
    options.rings = rad::kAnnualGlareRings;
    std::vector<rad::ReportDaylightGlare> out;
    for (const auto& o : file.observers)
        out.push_back({o, rad::summarise_glare_year(luminance.annual_glare(
                              skies, occupied, o.position, o.view, options))});
    return out;
}

// A daylight solution's year (--epw): the sensors' illuminance and metrics with their
// replicates, EN 17037's median and daylight hours, and the observers' glare.
struct DaylightYear {
    radfmt::AnnualData lux;
    rad::AnnualMetrics metrics;
    rad::AnnualReplicates replicates;
    rad::MedianDiffuse median;
    std::vector<std::uint8_t> daylight_hours;
};

DaylightYear daylight_year(const ReportArgs& a, const rad::CalcFile& file,
                           const radfmt::MeshData& mesh, const radfmt::RadiosityData& solution,
                           const radfmt::Header& rad_header, const rad::DaylightSensors& sensors,
                           const std::vector<rad::Vec3>& positions,
                           const std::vector<rad::Vec3>& normals,
                           const std::vector<std::uint8_t>& inside, rad::ReportInput& in) {
    DaylightYear out;
    const auto weather = rad::read_epw(a.epw);
    const auto occupied = rad::tool::occupied_hours(a.occupancy, weather);
    // The year's skies once, for the sensors and the observers' glare.
    const auto skies = rad::hourly_skies(weather, sensors.patches(), sensors.frame(), a.ground);
    out.lux = rad::annual_illuminance(sensors, skies, positions, normals, weather, occupied,
                                      a.quiet, nullptr, &out.replicates);
    out.metrics = rad::annual_metrics(out.lux, inside);
    out.daylight_hours = rad::en17037_daylight_hours(weather);
    out.median = rad::median_external_diffuse_illuminance(weather);
    in.weather = weather.place + " (" + a.epw + ")";
    in.occupancy = rad::tool::occupancy_text(a.occupancy);
    if (!file.observers.empty())
        in.daylight_glare =
            observers_daylight_glare(a, file, mesh, solution, rad_header, skies, occupied);
    return out;
}

// A surface's share of the year (its sensors first .. first + n): its metrics and their errors,
// and on a work plane EN 17037 by both methods.
void year_figures(const DaylightYear& year, rad::CalcKind kind, std::size_t first, std::size_t n,
                  const std::vector<std::uint8_t>& inside, rad::SurfaceDaylight& d) {
    d.annual = true;
    d.metrics = rad::summarise_sensor_metrics({year.metrics.sensors.begin() + long(first),
                                               year.metrics.sensors.begin() + long(first + n)},
                                              year.metrics.occupied_hours);
    for (const auto& m : d.metrics.sensors) d.da300.push_back(100 * m.da300);
    d.metric_errors = rad::annual_errors(year.replicates, d.metrics, first);
    if (kind != rad::CalcKind::WorkPlane) return;
    d.en17037 = rad::en17037_daylight_provision(d.factor, year.median.lux);
    std::vector<std::uint8_t> plane(inside.size(), 0);
    for (std::size_t k = first; k < first + n; ++k) plane[k] = !inside[k];
    d.en17037_hourly = rad::en17037_illuminance_method(year.lux, plane, year.daylight_hours);
    d.median_source = year.median.source;
}

// A daylight solution: each surface's daylight factor under the CIE overcast sky, and with
// --epw the year's metrics, by the functions rad-gather --surfaces calls, in its order.
void daylight_figures(const ReportArgs& a, const rad::CalcFile& file, const radfmt::MeshData& mesh,
                      const radfmt::RadiosityData& solution, const radfmt::Header& mesh_header,
                      const radfmt::Header& rad_header, rad::ReportInput& in) {
    if (!file.observers.empty() && a.epw.empty())
        throw rad::InputError(file.name + ": a daylight solution's observers get their daylight "
                                          "glare (DGP) over a year: give --epw FILE, or remove "
                                          "the observer lines");
    if (!file.cameras.empty())
        throw rad::InputError(file.name + ": views of a daylight solution are not in the report "
                                          "yet (rad-shade --sky renders them): remove the camera "
                                          "lines");
    const auto options = rad::tool::daylight_options(
        a.sky_samples, a.rays_option->count() ? a.options.rays : rad::tool::kDaylightRays,
        a.options.seed, a.options.accuracy, a.options.max_rays);
    const rad::DaylightSensors sensors(
        mesh, rad::daylight_solution(solution, rad_header, a.inputs[1]), options);
    const double metres = rad::metres_per_unit(mesh_header);
    in.room = rad::room_summary(mesh, metres);
    rad::refuse_daylight_unsupported(file);
    const auto grids = rad::surface_grids(file, metres);
    std::vector<rad::Vec3> positions, normals;
    rad::surface_sensors(file, grids, rad::bounds(mesh.vertices), positions, normals);
    rad::tool::SkyChoice overcast;
    overcast.sky = "cie-overcast";
    overcast.ground = a.ground;
    const auto sky = rad::tool::sky_of(overcast, "", sensors.frame());
    const auto lux = sensors.illuminance(sky, positions, normals, a.quiet);
    // Sensors inside furniture: no value (greyed on the plans), in no figure.
    const auto inside = sensors.inside(positions, normals);
    const auto year = a.epw.empty()
                          ? std::nullopt
                          : std::optional(daylight_year(a, file, mesh, solution, rad_header,
                                                        sensors, positions, normals, inside, in));
    std::size_t first = 0;
    for (std::size_t s = 0; s < grids.size(); ++s) {
        const auto n = std::size_t(grids[s].size());
        rad::SurfaceDaylight d;
        const double percent = 100 / sky.horizontal_illuminance();
        for (std::size_t k = first; k < first + n; ++k) {
            d.factor.push_back(inside[k] ? std::nan("") : percent * lux[k].total());
            d.factor_error.push_back(inside[k] ? std::nan("") : percent * lux[k].error());
            if (lux[k].at_budget && !inside[k]) d.at_budget.push_back(long(k - first));
        }
        d.summary = rad::summarise_daylight_factors(d.factor);
        d.mean_error = rad::illuminance_errors(d.factor, d.factor_error).mean;
        if (year) year_figures(*year, file.surfaces[s].kind, first, n, inside, d);
        d.verdict =
            rad::judge_daylight(d.summary.mean, d.annual ? &d.metrics.sda : nullptr,
                                d.annual ? &d.metrics.ase : nullptr, file.surfaces[s].required,
                                d.mean_error, d.metric_errors.sda);
        rad::ReportSurface surface;
        surface.surface = file.surfaces[s];
        surface.grid = grids[s];
        surface.daylight = std::move(d);
        in.surfaces.push_back(std::move(surface));
        first += n;
    }
    in.daylight = true;
    in.daylight_sky = sky.describe();
    in.metres_per_unit = metres;
    in.method = "Daylight at each point by daylight coefficients (rad-ff --sky, rad-solve "
                "--direct): the sky seen directly traced from the point (" +
                std::to_string(options.sky_side * options.sky_side) +
                " directions per sky patch, through glass), the light the room reflects from " +
                std::to_string(options.rays) +
                " cosine-weighted rays over each patch's radiosity per sky patch, the sun's beam "
                "traced each hour; seed " +
                std::to_string(options.seed) + ".";
}

void print_summary(const ReportArgs& a, const rad::ReportInput& in) {
    long failing = 0, points = 0;
    for (const auto& s : in.surfaces) {
        failing += s.daylight ? !s.daylight->verdict.passes() : !s.verdict.passes();
        points += s.grid.size();
    }
    char leni[64] = "";
    if (in.energy) std::snprintf(leni, sizeof leni, ", LENI %.2f kWh/(m^2 a)", in.energy->leni());
    std::fprintf(stderr,
                 "rad-report: %zu surface(s) (%ld points, %ld failing their requirements), %zu "
                 "observer(s)%s%s: %s%s%s\n",
                 in.surfaces.size(), points, failing, in.observers.size(),
                 in.daylight ? ", daylight" : "", leni, a.output.c_str(), a.pdf.empty() ? "" : ", ",
                 a.pdf.c_str());
}

// The title block's facts: project, date, this tool, the inputs' hashes, the solution's
// provenance.
rad::ReportInput title_of(const ReportArgs& a, const radfmt::Header& mesh_header,
                          const radfmt::Header& rad_header) {
    rad::ReportInput in;
    const auto& mesh_path = a.inputs[0];
    in.project = a.project.empty() ? std::filesystem::path(mesh_path).stem().string() : a.project;
    in.date = a.date.empty() ? today() : a.date;
    in.producer = rad::tool_version("rad-report");
    in.client = a.client;
    in.designer = a.designer;
    in.inputs = {{mesh_path, mesh_header.file_hash},
                 {a.inputs[1], rad_header.file_hash},
                 {a.surfaces, radfmt::hash_file(a.surfaces)}};
    for (const auto& record : rad_header.inputs) // what the solution was made from
        in.inputs.emplace_back(record.path + " (read by rad-solve)", record.hash);
    if (!a.epw.empty()) in.inputs.emplace_back(a.epw, radfmt::hash_file(a.epw));
    if (!a.occupancy.empty()) in.inputs.emplace_back(a.occupancy, radfmt::hash_file(a.occupancy));
    in.provenance = rad_header.chain();
    return in;
}

// The view at half size for the title block (each pixel the mean of four, in linear light):
// a quarter of the bytes the full view would add to the page a second time.
std::vector<std::uint8_t> thumbnail_png(const rad::Image& image, double exposure) {
    const int w = image.width / 2, h = image.height / 2;
    std::vector<std::uint8_t> pixels(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx)
                        sum +=
                            image.rgb[(std::size_t(2 * y + dy) * image.width + 2 * x + dx) * 3 + c];
                pixels[(std::size_t(y) * w + x) * 3 + c] = rad::to_srgb8(sum / 4 * exposure);
            }
    return rad::encode_png_rgb8(w, h, pixels);
}

// The number as a command line takes it back exactly enough (%.6g), and that value.
std::string view_number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

// The cameras' views: rad-shade --gather's image at 640 x 400, its luminaires drawn, exposed
// from the solution; the view as text first, and parsed back, so rad-shade given that text
// renders the same pixels.
std::vector<rad::ReportView> views_of(const ReportArgs& a, const rad::CalcFile& file,
                                      const rad::Gatherer& gatherer, const rad::LuminaireSet* set,
                                      const radfmt::RadiosityData& solution) {
    constexpr int kWidth = 640, kHeight = 400, kSupersampling = 2, kLuminanceDecades = 4;
    std::vector<rad::ReportView> views;
    if (file.cameras.empty()) return views;
    // A view is rad-shade --gather's image, whose pixels take the rays given, not rounds to an
    // accuracy: a gatherer of the same solution with the same options but that.
    auto options = a.options;
    options.accuracy = 0;
    const rad::Gatherer view_gatherer(gatherer.mesh(), solution.radiosity, options);
    const double exposure = rad::solution_exposure(gatherer.mesh(), solution.radiosity);
    const rad::Box box = rad::bounds(gatherer.mesh().vertices);
    const std::string batches = a.options.batches == rad::GatherOptions{}.batches
                                    ? ""
                                    : " --batches " + std::to_string(a.options.batches);
    for (const auto& c : file.cameras) {
        if (const auto why = rad::out_of_reach(c.position, box); !why.empty())
            throw rad::InputError(c.where, "the camera: " + why);
        const double half = c.angle_deg * std::numbers::pi / 360;
        const double vertical =
            360 / std::numbers::pi * std::atan(std::tan(half) * kHeight / kWidth);
        const auto v3 = [](const rad::Vec3& p) {
            return view_number(p[0]) + " " + view_number(p[1]) + " " + view_number(p[2]);
        };
        const std::string text = "-vp " + v3(c.position) + " -vd " + v3(c.direction) + " -vu " +
                                 v3(c.up) + " -vh " + view_number(c.angle_deg) + " -vv " +
                                 view_number(vertical);
        const auto view = rad::parse_view(text, c.where);
        // The irradiance cache at rad-shade's defaults, as the command below renders it.
        const rad::IrradianceCacheOptions cache;
        auto image = rad::render_gathered(view_gatherer, view, kWidth, kHeight, kSupersampling,
                                          a.quiet, set, {}, &cache);
        rad::ReportView out;
        // Per surface before the luminaires are drawn over what they hide, as rad-shade.
        out.surfaces = rad::surface_luminances(image, gatherer.mesh(), gatherer.scene(), view);
        if (set) rad::draw_luminaires(image, *set, gatherer.scene(), view, kSupersampling);
        out.scale = rad::luminance_scale(image, 0, kLuminanceDecades);
        out.falsecolor_png = rad::luminance_png(image, out.scale);
        std::vector<std::uint8_t> pixels(image.rgb.size());
        for (std::size_t i = 0; i < pixels.size(); ++i)
            pixels[i] = rad::to_srgb8(image.rgb[i] * exposure);
        out.name = c.name;
        out.width = kWidth, out.height = kHeight;
        out.png = rad::encode_png_rgb8(kWidth, kHeight, pixels);
        out.thumbnail_png = thumbnail_png(image, exposure);
        out.command = "rad-shade " + a.inputs[0] + " " + a.inputs[1] + " --view \"" + text +
                      "\" -x " + std::to_string(kWidth) + " -y " + std::to_string(kHeight) +
                      " --gather " + std::to_string(a.options.rays) + " --shadow-rays " +
                      std::to_string(a.options.shadow_rays) + batches + " --smooth " + a.smooth +
                      " --crease-angle " + view_number(a.options.crease_deg) +
                      " --png FILE --falsecolor FILE --luminance-table FILE";
        views.push_back(std::move(out));
    }
    return views;
}

// P_n: every luminaire's input watts from its photometric file.
double installed_watts(const rad::LuminaireSet& set) {
    double watts = 0;
    for (const auto& l : set.luminaires) {
        const auto& p = set.photometries[l.photometry];
        if (!(p.input_watts > 0))
            throw rad::InputError("--energy: " + p.source + " gives no input watts (luminaire " +
                                  l.name + "); LENI needs every luminaire's power");
        watts += p.input_watts;
    }
    return watts;
}

// Illuminance: the surfaces' lux, the luminaires, the observers' glare.
void lighting_figures(const ReportArgs& a, const rad::CalcFile& file, radfmt::MeshData& mesh,
                      const radfmt::RadiosityData& solution, const radfmt::Header& mesh_header,
                      const radfmt::Header& rad_header, rad::ReportInput& in,
                      std::optional<rad::LuminaireSet>& luminaires,
                      const std::optional<rad::LightingEnergyInputs>& energy) {
    if (!a.epw.empty() || !a.occupancy.empty())
        throw rad::InputError("--epw and --occupancy are for a daylight solution (rad-solve "
                              "--direct FILE.sky); " +
                              a.inputs[1] + " is not one");
    const rad::Gatherer gatherer(mesh, solution.radiosity, a.options);
    luminaires =
        rad::solution_luminaires(rad_header, a.inputs[1], a.direct, mesh, a.inputs[0], mesh_header);
    const auto* set = luminaires ? &*luminaires : nullptr;
    if (energy && !set)
        throw rad::InputError("--energy needs the luminaires' input power: " + a.inputs[1] +
                              " was not solved with a luminaires file (rad-solve --direct "
                              "FILE.lum)");
    const double metres = rad::metres_per_unit(mesh_header);
    const rad::Box box = rad::bounds(mesh.vertices);
    in.method = method_text(a, rad_header, set != nullptr);
    in.metres_per_unit = metres;
    in.luminaires = set;
    in.surfaces = surfaces_of(file, gatherer, set, box, metres, a.quiet);
    std::uint64_t sensors = 0;
    for (const auto& s : in.surfaces) sensors += std::uint64_t(s.grid.size());
    in.observers = observers_of(file, gatherer, set, box, sensors);
    in.views = views_of(a, file, gatherer, set, solution);
    power_area(a, file, metres, in);
    in.room = rad::room_summary(gatherer.mesh(), metres);
    if (energy) in.energy = rad::lighting_energy(*energy, installed_watts(*set), in.power_area_m2);
}

int report(ReportArgs& a) {
    const auto& mesh_path = a.inputs[0];
    const auto& rad_path = a.inputs[1];
    rad::tool::check_outputs({mesh_path, rad_path, a.surfaces, a.direct, a.epw, a.occupancy},
                             {{"-o", a.output}, {"--pdf", a.pdf}});
    a.options.smoothing = rad::parse_smoothing(a.smooth);
    std::optional<rad::LightingEnergyInputs> energy;
    if (!a.energy.empty()) energy = rad::parse_lighting_energy(a.energy);
    rad::ThreadLimit thread_limit(a.threads);
    const auto file = rad::read_calc_file(a.surfaces);
    radfmt::Header mesh_header, rad_header;
    auto mesh = radfmt::read_mesh(mesh_path, &mesh_header);
    const auto solution = radfmt::read_radiosity(rad_path, &rad_header);
    radfmt::require_same_geometry(rad_path, rad_header, solution.radiosity.size(), mesh_path, mesh,
                                  "run rad-ff and rad-solve on " + mesh_path + " again");
    rad::apply_recorded_overrides(mesh, rad_header);
    auto in = title_of(a, mesh_header, rad_header);
    std::optional<rad::LuminaireSet> luminaires;
    if (rad::is_daylight_solution(rad_header)) {
        if (energy)
            throw rad::InputError("--energy is for a solution lit by luminaires; " + rad_path +
                                  " is a daylight solution");
        daylight_figures(a, file, mesh, solution, mesh_header, rad_header, in);
    } else {
        lighting_figures(a, file, mesh, solution, mesh_header, rad_header, in, luminaires, energy);
    }

    // The room cut at each horizontal surface's plane, north and the point tables.
    for (auto& s : in.surfaces) s.cut = rad::plan_cut(mesh, s.grid, in.metres_per_unit);
    in.north_deg = std::isfinite(a.north) ? a.north
                   : rad::is_daylight_solution(rad_header)
                       ? rad::daylight_frame(rad_header, rad_path).north_deg
                       : std::nan("");
    in.point_tables = a.point_tables;
    const auto html = rad::report_html(in);
    radfmt::OutputBatch outputs;
    rad::tool::write_output(a.output, [&](std::FILE* out) { std::fputs(html.c_str(), out); });
    if (!a.pdf.empty())
        radfmt::write_atomically(
            a.pdf, [&](const std::filesystem::path& temp) { rad::print_pdf(html, temp); });
    outputs.commit();
    if (!a.quiet) print_summary(a, in);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "A lighting report: for each calculation surface of a CSV file (work planes, task\n"
        "areas, walls, ceilings, floors) the maintained illuminance's Em, Emin, Emax, U0 and\n"
        "Emin/Emax against the requirements the file gives, with a false-colour isolux plan;\n"
        "the luminaires' schedule, polar curves and installed power density; the UGR at the\n"
        "file's observers (CIE 117). One self-contained HTML page (no network), printable at\n"
        "A4, and with --pdf a PDF of it. Its numbers are the ones rad-gather --surfaces writes\n"
        "for the same inputs and options."};
    ReportArgs args;
    add_options(app, args);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    return rad::tool::run_tool("rad-report", [&] { return report(args); });
}
