// rad-gather: mesh + solved radiosity + points -> irradiance (or illuminance) at each point.
#include "gather_daylight.hpp"
#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/error.hpp"
#include "radiosity/falsecolour.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/huge_pages.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/melanopic.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/sensor_parts.hpp"
#include "radiosity/sensors.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/text_input.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

namespace {

// One sensor: where it is, which way it faces, and where it came from (for messages).
struct Sensor {
    long line = 0;
    rad::Vec3 position{0, 0, 0}, direction{0, 0, 0};
    std::string problem; // why it cannot be gathered
    rad::Irradiance result;
    rad::MelanopicSources::Result melanopic; // with --melanopic
};

// Where sensors come from: lines of a stream, or a generated grid.
class SensorSource {
  public:
    virtual ~SensorSource() = default;
    // Appends up to `count` sensors; false when there are no more.
    virtual bool next(std::vector<Sensor>& out, std::size_t count) = 0;
};

class LineSource final : public SensorSource {
  public:
    explicit LineSource(rad::LineReader& in) : in_(in) {}
    bool next(std::vector<Sensor>& out, std::size_t count) override {
        std::string text;
        while (out.size() < count && in_.next(text)) {
            if (!rad::is_sensor_line(text)) continue;
            auto pose = rad::parse_sensor_line(text);
            Sensor s{
                in_.line_number(), pose.position, pose.direction, std::move(pose.problem), {}, {}};
            out.push_back(std::move(s));
        }
        return !out.empty();
    }

  private:
    rad::LineReader& in_;
};

using Grid = rad::WorkPlaneGrid;

class GridSource final : public SensorSource {
  public:
    explicit GridSource(const Grid& grid) : grid_(grid) {}
    bool next(std::vector<Sensor>& out, std::size_t count) override {
        while (out.size() < count && index_ < grid_.size()) {
            Sensor s;
            s.line = index_ + 1;
            s.position = grid_.position(index_);
            s.direction = {0, 1, 0};
            out.push_back(s);
            ++index_;
        }
        return !out.empty();
    }

  private:
    Grid grid_;
    long index_ = 0;
};

std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

// A grid whose corners the ray tracer cannot reach is refused up front, as --points refuses
// such a point (its sensors are not "inside objects": they are too far to trace from).
void check_grid_reach(const Grid& grid, const rad::Box& box) {
    for (const double x : {grid.x0, grid.x1})
        for (const double z : {grid.z0, grid.z1})
            if (const auto why = rad::out_of_reach({x, grid.y, z}, box); !why.empty())
                throw rad::InputError("--grid: its corner (" + number_text(x) + ", " +
                                      number_text(grid.y) + ", " + number_text(z) + "): " + why);
}

// "123.4 ± 0.56" (no ± when the error is not known).
std::string with_error(double value, double error) {
    char text[48];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text + rad::tool::error_suffix(error);
}

// What lighting designers report of a work plane, over the sensors with a value (lux), each
// figure with its standard error.
void print_work_plane(const std::vector<double>& lux, const std::vector<double>& error) {
    const auto stats = rad::illuminance_stats(lux);
    if (stats.count == 0) {
        std::fprintf(stderr,
                     "rad-gather: work plane: no sensor has a value (%ld inside or behind "
                     "objects: nan)\n",
                     stats.without_value);
        return;
    }
    const auto errors = rad::illuminance_errors(lux, error);
    char u0[64];
    std::snprintf(u0, sizeof u0, "%.3f%s", stats.u0(), rad::tool::error_suffix(errors.u0).c_str());
    std::fprintf(stderr,
                 "rad-gather: work plane: %ld sensor(s) with a value, %ld inside or behind "
                 "objects (nan): Emin %s lx, Eavg %s lx, Emax %s lx, U0 = Emin/Eavg = %s "
                 "(± one standard error)\n",
                 stats.count, stats.without_value, with_error(stats.min, errors.min).c_str(),
                 with_error(stats.mean, errors.mean).c_str(),
                 with_error(stats.max, errors.max).c_str(), u0);
}

// What the command line says.
struct GatherArgs {
    std::vector<std::string> inputs;
    std::string mesh_path, rad_path, points_path, output, grid_text, png, smooth = "crease";
    std::string surfaces_path;
    std::string direct_path, rows;
    bool merge = false;
    rad::GatherOptions options;
    bool lux = false, header = false, keep_going = false, quiet = false, error = false;
    bool estimate = false, melanopic = false;
    std::vector<std::string> spectra; // --spectrum
    double lux_max = 0;
    int threads = 0;
    rad::tool::DaylightArgs daylight;
    CLI::Option* rays_option = nullptr;
};

// The inputs and outputs.
void add_file_options(CLI::App& app, GatherArgs& a) {
    app.add_option("MESH RADIOSITY", a.inputs,
                   "Patch mesh from rad-mesh and radiosity from rad-solve for it (with --merge: "
                   "the part files to join)")
        ->required();
    app.add_option("--points", a.points_path, "Read the points from this file (default: stdin)");
    app.add_option("-o,--output", a.output, "Write to this file (default: stdout)");
    app.add_option("--direct", a.direct_path,
                   "The luminaires file (.lum) the solution was solved with, when it has moved "
                   "(default: the one rad-solve --direct recorded); its luminaires' direct "
                   "light is computed exactly at each point (tables and visibility rays)");
}

// What is written, and the work plane.
void add_output_options(CLI::App& app, GatherArgs& a) {
    app.add_flag("--lux", a.lux,
                 "Write illuminance in lux, one number per line: 179 lm/W x (0.265 R + 0.670 G "
                 "+ 0.065 B), Radiance's convention");
    app.add_flag("--error", a.error,
                 "Write each value's standard error beside it (from the point's independent "
                 "batches of rays: --batches): 'lux error' with --lux, 'r g b er eg eb' "
                 "without, a lux_error column with --surfaces");
    app.add_flag("--header", a.header, "Start the output with a '#' provenance line");
    app.add_flag("--melanopic", a.melanopic,
                 "Also the melanopic EDI (lx; CIE S 026: melanopic equivalent daylight (D65) "
                 "illuminance): with --lux a second column ('lux melanopic' or 'lux error "
                 "melanopic error'); with --surfaces each observer's eye (facing its view, "
                 "level), its M/P ratio, on stderr. Each light group's light is weighed by its "
                 "spectrum (--spectrum) in the three bands the chain's RGB stands for");
    app.add_option("--spectrum", a.spectra,
                   "--melanopic: a light group's spectrum, GROUP=SPEC, or SPEC for every group "
                   "not named (and for a solution without groups); repeatable. SPEC: d65, a "
                   "(CIE illuminant A), cct:K (a blackbody) or a CSV file of wavelength_nm,value "
                   "rows. Default: the group's luminaires' lamp colour temperature (the layout's "
                   "cct column, EULUMDAT's lamps) as a blackbody");
    app.add_flag("--keep-going", a.keep_going,
                 "Write 'nan nan nan' for a point that cannot be gathered (bad line, zero "
                 "direction, inside an object) and go on, instead of stopping there");
    app.add_option("--grid", a.grid_text,
                   "Instead of reading points: upward sensors on a work plane, \"x0 z0 x1 z1 y "
                   "nx nz\" (cell centres, height y, rows of constant z from z0, x fastest); "
                   "sensors inside furniture have no value (nan, grey in the PNG, counted), and "
                   "the summary gives Emin, Eavg, Emax and U0 = Emin/Eavg of the others");
    app.add_option("--surfaces", a.surfaces_path,
                   "Instead of reading points: the sensors of the calculation surfaces in this "
                   "CSV (formats/README.md: work planes, task areas, walls, ceilings, by "
                   "EN 12464-1's grid rule); writes 'surface,index,column,row,x,y,z,lux' lines "
                   "and each surface's Em, Emin, Emax, U0 and verdict on stderr, the numbers "
                   "rad-report shows; daylight: the last column is df (--daylight-factor) or "
                   "lux (--sky), and --annual's --metrics lines start with the surface's "
                   "columns");
    app.add_flag("--estimate", a.estimate,
                 "With --surfaces: gather the first " + std::to_string(rad::kEstimateSensors) +
                     " sensors, say how long the whole run would take, and stop: no output. "
                     "Without it, rad-gather says so before runs of over 10 s");
    app.add_option("--png", a.png,
                   "With --grid: also write a false-colour PNG of the illuminance (lux) with a "
                   "legend");
    app.add_option("--lux-max", a.lux_max,
                   "--png: the legend's top (lux), the same for every plane drawn with it "
                   "(default: a round number at or above the plane's largest value; values "
                   "above it get the top colour)")
        ->check(rad::tool::finite_range(0, 1e30));
}

// Threads, the seed, quiet, and sharding.
void add_run_options(CLI::App& app, GatherArgs& a) {
    rad::tool::add_common_options(
        app, {.threads = &a.threads,
              .seed = &a.options.seed,
              .seed_help = "each point's own random stream (seed, point index)",
              .quiet = &a.quiet,
              .shows_progress = true,
              .rows = &a.rows,
              .merge = &a.merge,
              .tool = "rad-gather",
              .rows_unit = "sensors",
              .rows_extra = "; the sensors of --points FILE, --grid or --surfaces, in order",
              .merge_result = "-o, in order: the bytes one run would have written"});
}

// Combinations that cannot work.
void check_combinations(const GatherArgs& a) {
    if (!a.rows.empty()) {
        if (a.output.empty()) throw rad::InputError("--rows writes a part file: give -o FILE");
        if (a.points_path.empty() && a.grid_text.empty())
            throw rad::InputError("--rows splits a --points FILE or a --grid (standard input "
                                  "cannot be counted and read again)");
        if (!a.png.empty())
            throw rad::InputError("--png draws the whole plane: give it to one run of the "
                                  "--grid, not to a --rows part");
    }
    if (!a.spectra.empty() && !a.melanopic)
        throw rad::InputError("--spectrum weighs light for --melanopic: add it");
    const bool daylight = rad::tool::wants_daylight(a.daylight);
    if (a.melanopic && !a.lux && a.surfaces_path.empty() && !daylight)
        throw rad::InputError("--melanopic writes melanopic EDI beside lux: add --lux (or give "
                              "--surfaces with observers)");
    if (a.melanopic &&
        (a.daylight.annual || !a.daylight.glare.empty() || !a.daylight.sunlight.empty()))
        throw rad::InputError("--melanopic gives melanopic EDI under one sky (--sky) or from "
                              "luminaires and emitters: not with --annual, --glare or "
                              "--sunlight-exposure");
    if (a.estimate && a.surfaces_path.empty())
        throw rad::InputError("--estimate measures a --surfaces run: give --surfaces FILE");
    if (a.lux_max > 0 && a.png.empty())
        throw rad::InputError("--lux-max scales the --png of a --grid: give --png FILE");
    if (!a.png.empty() && a.grid_text.empty())
        throw rad::InputError("--png draws a --grid: give --grid \"x0 z0 x1 z1 y nx nz\"");
    if (!a.grid_text.empty() && !a.points_path.empty())
        throw rad::InputError("give --grid or --points, not both");
    if (!a.surfaces_path.empty() && (!a.grid_text.empty() || !a.points_path.empty() ||
                                     !a.rows.empty() || !a.png.empty() || a.lux || a.keep_going))
        throw rad::InputError("--surfaces writes lux at its own sensors: not with --points, "
                              "--grid, --rows, --png, --lux or --keep-going");
}

// Streams blocks of sensors: parsed, gathered in parallel, written in order; keeps what the
// summary and the work plane's picture need.
class GatherRun {
  public:
    GatherRun(const GatherArgs& args, const rad::Gatherer& gatherer, const rad::Box& scene_box,
              SensorSource& source, std::string source_name, rad::RowRange range,
              const rad::LuminaireSet* luminaires, const rad::MelanopicSources* melanopic)
        : args_(args), gatherer_(gatherer), luminaires_(luminaires), melanopic_(melanopic),
          scene_box_(scene_box), source_(source), source_name_(std::move(source_name)),
          range_(range),
          progress_("rad-gather", range.end == rad::RowRange{}.end ? 0 : range.end - range.begin,
                    args.quiet) {}

    // Sensors range.begin to range.end of the source (each drawing its rays from its index
    // in the whole source, so parts gather what one run does).
    void stream(std::FILE* out, const std::string& preamble) {
        if (!preamble.empty()) std::fputs(preamble.c_str(), out);
        std::vector<Sensor> block;
        constexpr std::uint64_t kBlock = 4096;
        for (std::uint64_t skipped = 0; skipped < range_.begin; skipped += block.size())
            if (block.clear(), !source_.next(block, std::min(kBlock, range_.begin - skipped)))
                return;
        const std::uint64_t wanted = range_.end - range_.begin;
        while (block.clear(),
               std::uint64_t(written_) < wanted &&
                   source_.next(block, std::min(kBlock, wanted - std::uint64_t(written_)))) {
            gather(block);
            write(block, out);
            written_ += static_cast<long>(block.size());
            if (std::ferror(out)) {
                if (out == stdout && rad::tool::stdout_reader_gone())
                    return; // `| head`: a normal end, as for every tool
                throw rad::SystemError("cannot write the output: " +
                                       std::string(std::strerror(errno)));
            }
        }
    }
    void finish() { progress_.finish(); }
    long written() const { return written_; }
    long problems() const { return problems_; }
    const std::string& first_problem() const { return first_problem_; }
    const std::vector<double>& grid_lux() const { return grid_lux_; }
    const std::vector<double>& grid_error() const { return grid_error_; }
    long at_budget() const { return at_budget_; }
    const std::string& at_budget_names() const { return at_budget_names_; }
    double mean_rays() const { return gathered_ ? double(rays_) / double(gathered_) : 0; }

  private:
    void gather(std::vector<Sensor>& block) {
        tbb::parallel_for(std::size_t(0), block.size(), [&](std::size_t k) {
            auto& s = block[k];
            const auto index = range_.begin + std::uint64_t(written_) + k;
            if (s.problem.empty())
                s.result = rad::gather_sensor(gatherer_, luminaires_, scene_box_, s.position,
                                              s.direction, index, s.problem);
            if (s.problem.empty() && melanopic_)
                s.melanopic = melanopic_->at(s.result, s.position, s.direction, index, scene_box_);
            progress_.advance(1);
        });
    }
    void write(const std::vector<Sensor>& block, std::FILE* out) {
        const bool grid = !args_.grid_text.empty();
        for (const auto& s : block) {
            if (!s.problem.empty()) {
                const std::string where = source_name_ + ":" + std::to_string(s.line);
                if (!args_.keep_going)
                    throw rad::InputError(where + ": " + s.problem +
                                          " (--keep-going writes nan and goes on)");
                if (problems_++ == 0) first_problem_ = where + ": " + s.problem;
                const char* lux = args_.melanopic
                                      ? (args_.error ? "nan nan nan nan\n" : "nan nan\n")
                                      : (args_.error ? "nan nan\n" : "nan\n");
                std::fputs(
                    args_.lux ? lux : (args_.error ? "nan nan nan nan nan nan\n" : "nan nan nan\n"),
                    out);
                if (grid) grid_lux_.push_back(std::nan("")), grid_error_.push_back(std::nan(""));
                continue;
            }
            const auto h = s.result.total();
            const double value = rad::lux(h);
            const double error = rad::kRadianceEfficacy * s.result.luminous_error;
            tally(s);
            if (grid) grid_lux_.push_back(value), grid_error_.push_back(error);
            const auto& mel = s.melanopic;
            if (args_.lux && args_.melanopic && args_.error)
                std::fprintf(out, "%.6g %.3g %.6g %.3g\n", value, error, mel.edi, mel.error);
            else if (args_.lux && args_.melanopic)
                std::fprintf(out, "%.6g %.6g\n", value, mel.edi);
            else if (args_.lux && args_.error)
                std::fprintf(out, "%.6g %.3g\n", value, error);
            else if (args_.lux)
                std::fprintf(out, "%.6g\n", value);
            else if (args_.error)
                std::fprintf(out, "%.6g %.6g %.6g %.3g %.3g %.3g\n", h[0], h[1], h[2],
                             s.result.error[0], s.result.error[1], s.result.error[2]);
            else
                std::fprintf(out, "%.6g %.6g %.6g\n", h[0], h[1], h[2]);
        }
    }
    // What the sampling took: the rays, and the points that stopped at the budget.
    void tally(const Sensor& s) {
        rays_ += s.result.rays_cast;
        ++gathered_;
        if (!s.result.at_budget) return;
        if (at_budget_++ < 3)
            at_budget_names_ += (at_budget_names_.empty() ? "" : ", ") + source_name_ + ":" +
                                std::to_string(s.line);
    }

    const GatherArgs& args_;
    const rad::Gatherer& gatherer_;
    const rad::LuminaireSet* luminaires_;
    const rad::MelanopicSources* melanopic_;
    const rad::Box& scene_box_;
    SensorSource& source_;
    std::string source_name_;
    rad::RowRange range_;
    rad::Progress progress_;
    long written_ = 0, problems_ = 0;
    std::string first_problem_;
    std::vector<double> grid_lux_, grid_error_; // for --png and the summary
    long at_budget_ = 0, gathered_ = 0;
    long long rays_ = 0;
    std::string at_budget_names_;
};

// The points that stopped at --max-rays before --accuracy, counted and named (the first few).
void print_at_budget(const rad::GatherOptions& o, long count, const std::string& names) {
    rad::tool::warn_at_budget("point(s)", count, o.max_rays, o.accuracy, names);
}

// The problems met (or the work plane's figures), then the summary.
void report(const GatherArgs& a, const GatherRun& run, double seconds) {
    print_at_budget(a.options, run.at_budget(), run.at_budget_names());
    if (!a.grid_text.empty()) {
        print_work_plane(run.grid_lux(), run.grid_error());
    } else if (run.problems()) {
        std::fprintf(stderr,
                     "rad-gather: warning: %ld point(s) could not be gathered and were written "
                     "as nan; the first: %s\n",
                     run.problems(), run.first_problem().c_str());
    }
    if (a.quiet) return;
    const long written = run.written();
    std::string rays = a.options.exact ? "exact" : std::to_string(a.options.rays) + " rays";
    if (a.options.accuracy > 0 && !a.options.exact && a.options.rays > 0) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "%.0f rays on average (to %g%% standard error, at most %d)", run.mean_rays(),
                      100 * a.options.accuracy, a.options.max_rays);
        rays = text;
    }
    std::fprintf(stderr,
                 "rad-gather: %ld point(s) in %.3f s (%.0f/s), %s indirect, %d shadow ray(s) per "
                 "point's first round\n",
                 written, seconds, seconds > 0 ? written / seconds : 0.0, rays.c_str(),
                 a.options.shadow_rays);
}

// The sensors of a points file (its lines but blank ones and comments), for --rows K/N.
std::uint64_t count_sensors(const std::string& path) {
    rad::LineReader in(path);
    std::string text;
    std::uint64_t count = 0;
    while (in.next(text)) count += rad::is_sensor_line(text);
    return count;
}

// --merge: the parts into the output one run would have written.
int merge_parts(const GatherArgs& a) {
    if (a.output.empty()) throw rad::InputError("--merge writes -o FILE: give it");
    rad::tool::check_outputs(a.inputs, {{"-o", a.output}});
    const auto sensors = rad::merge_sensor_parts(a.inputs, a.output);
    if (!a.quiet)
        std::fprintf(stderr, "rad-gather: merged %zu part(s): %llu sensor(s)\n", a.inputs.size(),
                     static_cast<unsigned long long>(sensors));
    return 0;
}

// The --header line of a run with this command (empty without --header).
std::string header_line(const GatherArgs& a, const std::string& command,
                        const radfmt::Header& mesh_header, const radfmt::Header& rad_header) {
    if (!a.header) return "";
    return "# " + rad::tool_version("rad-gather") + ": " + command + "; mesh " + a.mesh_path + " " +
           mesh_header.file_hash + "; radiosity " + a.rad_path + " " + rad_header.file_hash +
           "; columns: " + (a.lux ? "illuminance (lux)" : "irradiance r g b (W/m^2)");
}

// What a part says of itself: which sensors, of what, by which command.
std::string part_preamble(const GatherArgs& a, const Grid& grid, rad::RowRange range,
                          std::uint64_t total, const radfmt::Header& mesh_header,
                          const radfmt::Header& rad_header, int argc, char** argv) {
    rad::SensorPart part;
    part.begin = range.begin;
    part.end = range.end;
    part.total = total;
    part.inputs =
        mesh_header.file_hash + " " + rad_header.file_hash + " " +
        (a.grid_text.empty() ? radfmt::hash_file(a.points_path)
                             : "grid " + std::to_string(grid.nx) + "x" + std::to_string(grid.nz));
    part.command = rad::unsharded_command(argc, argv);
    part.header_line = header_line(a, part.command, mesh_header, rad_header);
    return rad::sensor_part_preamble(part);
}

// The sensors this run gathers (all, or a part's), and what the output starts with: one
// run's --header line, or a part's preamble.
std::string sensors_and_preamble(const GatherArgs& a, const Grid& grid,
                                 const radfmt::Header& mesh_header,
                                 const radfmt::Header& rad_header, int argc, char** argv,
                                 rad::RowRange& range) {
    range = {};
    if (a.rows.empty()) {
        if (!a.grid_text.empty()) range.end = std::uint64_t(grid.size());
        const auto line = header_line(a, radfmt::command_line(argc, argv), mesh_header, rad_header);
        return line.empty() ? "" : line + "\n";
    }
    const std::uint64_t total =
        a.grid_text.empty() ? count_sensors(a.points_path) : std::uint64_t(grid.nx) * grid.nz;
    range = rad::parse_rows(a.rows, total, "the sensors");
    return part_preamble(a, grid, range, total, mesh_header, rad_header, argc, argv);
}

// Daylight's sensors from --points or --grid, every one read first.
void read_daylight_sensors(const GatherArgs& a, const Grid& grid, const rad::Box& box,
                           rad::tool::DaylightRun& run) {
    std::unique_ptr<rad::LineReader> points;
    std::unique_ptr<SensorSource> source;
    if (a.grid_text.empty()) {
        points = std::make_unique<rad::LineReader>(a.points_path);
        source = std::make_unique<LineSource>(*points);
    } else {
        source = std::make_unique<GridSource>(grid);
        run.grid_columns = int(grid.nx);
        run.grid_rows = int(grid.nz);
    }
    std::vector<Sensor> sensors;
    while (source->next(sensors, sensors.size() + 4096)) {
        if (sensors.size() == run.positions.size()) break;
        for (std::size_t k = run.positions.size(); k < sensors.size(); ++k) {
            const auto& s = sensors[k];
            const auto where = a.points_path.empty() ? std::string("<stdin>") : a.points_path;
            if (!s.problem.empty())
                throw rad::InputError(where + ":" + std::to_string(s.line) + ": " + s.problem);
            if (const auto why = rad::out_of_reach(s.position, box); !why.empty())
                throw rad::InputError(where + ":" + std::to_string(s.line) + ": " + why);
            run.positions.push_back(s.position);
            run.normals.push_back(s.direction);
        }
    }
}

// A surface sensor's first CSV columns: "surface,index,column,row".
std::string sensor_label(const rad::CalcSurface& surface, const rad::SurfaceGrid& grid, long k) {
    return rad::csv_field(surface.name) + "," + std::to_string(k) + "," +
           std::to_string(k % grid.columns) + "," + std::to_string(k / grid.columns);
}

// --surfaces' file, which must name a surface (or, for --melanopic, an observer).
rad::CalcFile read_surfaces_file(const std::string& path, bool observers_suffice = false) {
    auto file = rad::read_calc_file(path);
    if (observers_suffice && !file.observers.empty()) return file;
    if (file.surfaces.empty())
        throw rad::InputError(path + ": it names no surface (observers and cameras are for "
                                     "rad-report): add one");
    return file;
}

// Daylight's sensors from --surfaces: every surface's grid, in order, each line labelled.
void surface_daylight_sensors(const GatherArgs& a, double metres_per_unit, const rad::Box& box,
                              rad::tool::DaylightRun& run) {
    const auto file = read_surfaces_file(a.surfaces_path);
    rad::refuse_daylight_unsupported(file);
    const auto grids = rad::surface_grids(file, metres_per_unit);
    rad::surface_sensors(file, grids, box, run.positions, run.normals);
    for (std::size_t s = 0; s < grids.size(); ++s) {
        run.surfaces.emplace_back(file.surfaces[s].name, std::size_t(grids[s].size()));
        run.reference_planes.push_back(file.surfaces[s].kind == rad::CalcKind::WorkPlane);
        for (long k = 0; k < grids[s].size(); ++k)
            run.labels.push_back(sensor_label(file.surfaces[s], grids[s], k));
    }
}

// Daylight (--sky, --epw --annual): every sensor read first, then gathered in parallel.
int daylight(const GatherArgs& a, const radfmt::MeshData& mesh,
             const radfmt::RadiosityData& solution, const radfmt::Header& rad_header,
             const Grid& grid, const radfmt::Header& mesh_header, int argc, char** argv) {
    if (!a.rows.empty() || a.options.exact || (a.keep_going && a.grid_text.empty()))
        throw rad::InputError("daylight takes neither --rows, --exact nor --keep-going");
    rad::tool::DaylightRun run;
    run.mesh = &mesh;
    run.solution = &solution;
    run.rad_header = &rad_header;
    run.rad_path = a.rad_path;
    run.output = a.output;
    run.png = a.png;
    run.rays = a.rays_option->count() ? a.options.rays : rad::tool::kDaylightRays;
    run.accuracy = a.options.accuracy;
    run.max_rays = a.options.max_rays;
    run.seed = a.options.seed;
    run.quiet = a.quiet;
    run.error = a.error;
    run.melanopic = a.melanopic;
    run.spectra = a.spectra;
    run.lux_max = a.lux_max;
    run.command = radfmt::command_line(argc, argv);
    run.inputs = {a.mesh_path, a.rad_path};
    for (const auto* extra :
         {&a.points_path, &a.surfaces_path, &a.daylight.epw, &a.daylight.occupancy})
        if (!extra->empty()) run.inputs.push_back(*extra);
    for (const auto& state : a.daylight.shaded) run.inputs.push_back(state);
    if (a.header) run.header_line = header_line(a, run.command, mesh_header, rad_header);
    run.direct_path = a.direct_path;
    if (rad::tool::wants_glare(a.daylight)) return rad::tool::gather_daylight(a.daylight, run);
    const rad::Box box = rad::bounds(mesh.vertices);
    if (a.surfaces_path.empty())
        read_daylight_sensors(a, grid, box, run);
    else
        surface_daylight_sensors(a, rad::metres_per_unit(mesh_header), box, run);
    if (run.positions.empty()) throw rad::InputError("no sensors: give --points FILE or --grid");
    return rad::tool::gather_daylight(a.daylight, run);
}

// What a verdict says: met or not, and whether a margin lies within the calculation's
// uncertainty (two standard errors).
const char* verdict_text(const rad::Verdict& verdict) {
    if (verdict.passes())
        return verdict.close() ? ": meets its requirements, within the calculation's uncertainty"
                               : ": meets its requirements";
    return verdict.close() ? ": FAILS its requirements, within the calculation's uncertainty"
                           : ": FAILS its requirements";
}

// A surface's figures and verdict, as rad-report shows them.
// A cylindrical surface's modelling index, for its line; else nothing.
std::string modelling_text(const rad::SurfaceGrid& grid, const rad::GatheredSurface& gathered) {
    if (!grid.cylindrical || grid.semi) return "";
    const auto m = rad::modelling_index(gathered.lux, gathered.horizontal);
    if (m.count == 0) return ", modelling Ez/Eh -";
    char text[96];
    std::snprintf(text, sizeof text, ", modelling Ez/Eh %.2f (%.2f to %.2f)", m.mean, m.min, m.max);
    return text;
}

void print_surface(const rad::CalcSurface& surface, const rad::SurfaceGrid& grid,
                   const rad::GatheredSurface& gathered) {
    const auto stats = rad::illuminance_stats(gathered.lux);
    const bool required = surface.required.of_light();
    if (stats.count == 0) {
        std::fprintf(stderr,
                     "rad-gather: %s (%s): no sensor has a value (%ld inside or behind objects: "
                     "nan)%s\n",
                     surface.name.c_str(), rad::calc_kind_name(surface.kind), stats.without_value,
                     required ? ": FAILS its requirements" : "");
        return;
    }
    const auto errors = rad::illuminance_errors(gathered.lux, gathered.error);
    const auto verdict = rad::judge(stats, surface.required, errors);
    std::fprintf(stderr,
                 "rad-gather: %s (%s, %ld x %ld sensors at %.3g m, %ld without a value): Em %s "
                 "lx, Emin %s lx, Emax %s lx, U0 %.3f%s, Emin/Emax %.3f%s%s\n",
                 surface.name.c_str(), rad::calc_kind_name(surface.kind), grid.columns, grid.rows,
                 grid.spacing_m, stats.without_value, with_error(stats.mean, errors.mean).c_str(),
                 with_error(stats.min, errors.min).c_str(),
                 with_error(stats.max, errors.max).c_str(), stats.u0(),
                 rad::tool::error_suffix(errors.u0).c_str(), stats.min_over_max(),
                 modelling_text(grid, gathered).c_str(), required ? verdict_text(verdict) : "");
    rad::tool::warn_facing_too_close("rad-gather", surface, gathered.facing_distance_m);
}

// --melanopic at each observer's eye: the illuminance on a level sensor facing its view
// (the eye's vertical illuminance), the melanopic EDI and their ratio (M/P), on stderr.
void print_observers_melanopic(const rad::CalcFile& file, const rad::Gatherer& gatherer,
                               const rad::LuminaireSet* luminaires, const rad::Box& box,
                               const rad::MelanopicSources& melanopic) {
    if (file.observers.empty())
        throw rad::InputError(file.name + ": --melanopic gives the light at observers' eyes, "
                                          "and the file has no observer line (formats/README.md)");
    // Streams of their own, apart from every sensor's (seeded by its index from 0).
    constexpr std::uint64_t kObserverStreams = std::uint64_t(1) << 40;
    for (std::size_t k = 0; k < file.observers.size(); ++k) {
        const auto& o = file.observers[k];
        const double level = std::hypot(o.view[0], o.view[2]);
        if (level < 1e-6)
            throw rad::InputError(o.where, "the observer looks straight up or down: the eye's "
                                           "vertical illuminance needs a view with a level part");
        const rad::Vec3 facing{o.view[0] / level, 0, o.view[2] / level};
        std::string problem;
        const auto index = kObserverStreams + k;
        const auto e =
            rad::gather_sensor(gatherer, luminaires, box, o.position, facing, index, problem);
        if (!problem.empty()) throw rad::InputError(o.where, "the observer's eye: " + problem);
        const auto m = melanopic.at(e, o.position, facing, index, box);
        const double ev = rad::lux(e.total());
        const double ratio = ev > 0 ? m.edi / ev : 0.0;
        std::fprintf(stderr,
                     "rad-gather: observer %s: Ev %s lx (at the eye, level, facing its view), "
                     "melanopic EDI %s lx, mel-DER %.3f at the eye (WELL: %.0f EML, M/P %.3f)\n",
                     o.name.c_str(),
                     with_error(ev, rad::kRadianceEfficacy * e.luminous_error).c_str(),
                     with_error(m.edi, m.error).c_str(), ratio, m.edi / rad::kMelanopicEdiPerEml,
                     ratio / rad::kMelanopicEdiPerEml);
    }
}

// --surfaces: every calculation surface's sensors, one CSV line each, and their figures.
void gather_surfaces(const GatherArgs& a, const rad::Gatherer& gatherer,
                     const rad::LuminaireSet* luminaires, const rad::Box& scene_box,
                     double metres_per_unit, int argc, char** argv,
                     const radfmt::Header& mesh_header, const radfmt::Header& rad_header,
                     const rad::MelanopicSources* melanopic) {
    const auto file = read_surfaces_file(a.surfaces_path, melanopic != nullptr);
    if (melanopic) print_observers_melanopic(file, gatherer, luminaires, scene_box, *melanopic);
    if (file.surfaces.empty()) return;
    const auto grids = rad::surface_grids(file, metres_per_unit);
    // Long runs say what they will cost first; --estimate stops there.
    const auto gathered = rad::gather_surfaces(
        gatherer, luminaires, scene_box, grids, a.quiet, [&](const rad::SensorsEstimate& e) {
            if (a.estimate || !a.quiet)
                rad::tool::say_sensors_estimate("rad-gather", e, a.estimate);
            return !a.estimate;
        });
    if (a.estimate) return;
    const auto header = header_line(a, radfmt::command_line(argc, argv), mesh_header, rad_header);
    rad::tool::write_output(a.output, [&](std::FILE* out) {
        if (!header.empty()) std::fprintf(out, "%s\n", header.c_str());
        std::fputs(a.error ? "surface,index,column,row,x,y,z,lux,lux_error\n"
                           : "surface,index,column,row,x,y,z,lux\n",
                   out);
        for (std::size_t s = 0; s < grids.size(); ++s)
            for (long k = 0; k < grids[s].size(); ++k) {
                const auto p = grids[s].position(k);
                const auto i = std::size_t(k);
                std::fprintf(out, "%s,%.6g,%.6g,%.6g,%.6g",
                             sensor_label(file.surfaces[s], grids[s], k).c_str(), p[0], p[1], p[2],
                             gathered[s].lux[i]);
                if (a.error) std::fprintf(out, ",%.3g", gathered[s].error[i]);
                std::fputc('\n', out);
            }
    });
    long stopped = 0;
    std::string names;
    for (std::size_t s = 0; s < grids.size(); ++s)
        for (const long k : gathered[s].at_budget)
            if (stopped++ < 3)
                names += (names.empty() ? "" : ", ") + file.surfaces[s].name + " sensor " +
                         std::to_string(k);
    print_at_budget(a.options, stopped, names);
    if (a.quiet) return;
    for (std::size_t s = 0; s < grids.size(); ++s)
        print_surface(file.surfaces[s], grids[s], gathered[s]);
}

// --melanopic: the solution's light sources by spectrum, said on stderr.
std::unique_ptr<rad::MelanopicSources> melanopic_sources(const GatherArgs& a,
                                                         const radfmt::MeshData& mesh,
                                                         const radfmt::RadiosityData& solution,
                                                         const radfmt::Header& rad_header,
                                                         const rad::LuminaireSet* luminaires) {
    if (!a.melanopic) return nullptr;
    auto sources = std::make_unique<rad::MelanopicSources>(mesh, solution, rad_header, luminaires,
                                                           a.spectra, a.options);
    if (!a.quiet)
        for (const auto& line : sources->describe())
            std::fprintf(stderr, "rad-gather: melanopic: %s\n", line.c_str());
    return sources;
}

int gather(GatherArgs& a, int argc, char** argv) {
    if (a.merge) return merge_parts(a);
    if (a.inputs.size() != 2)
        throw rad::InputError("give MESH and RADIOSITY (" + std::to_string(a.inputs.size()) +
                              " file(s) given; several are for --merge)");
    a.mesh_path = a.inputs[0];
    a.rad_path = a.inputs[1];
    auto inputs = std::vector<std::string>{a.mesh_path, a.rad_path, a.points_path, a.surfaces_path};
    inputs.insert(inputs.end(), a.daylight.shaded.begin(), a.daylight.shaded.end());
    rad::tool::check_outputs(inputs, {{"-o", a.output},
                                      {"--png", a.png},
                                      {"--metrics", a.daylight.metrics},
                                      {"--shading-log", a.daylight.shading_log}});
    check_combinations(a);
    const auto grid = a.grid_text.empty() ? Grid{} : rad::parse_work_plane_grid(a.grid_text);
    // A work plane runs through furniture: a sensor inside it has no value, not an error.
    if (!a.grid_text.empty()) a.keep_going = true;
    a.options.smoothing = rad::parse_smoothing(a.smooth);
    rad::ThreadLimit thread_limit(a.threads);
    radfmt::OutputBatch outputs;

    radfmt::Header mesh_header, rad_header;
    auto mesh = radfmt::read_mesh(a.mesh_path, &mesh_header);
    const auto solution = radfmt::read_radiosity(a.rad_path, &rad_header);
    radfmt::require_same_geometry(a.rad_path, rad_header, solution.radiosity.size(), a.mesh_path,
                                  mesh, "run rad-ff and rad-solve on " + a.mesh_path + " again");
    // E and rho as solved (rad-solve --emission/--reflectance overrides included).
    rad::apply_recorded_overrides(mesh, rad_header);
    if (rad::tool::wants_daylight(a.daylight)) {
        if (a.estimate)
            throw rad::InputError("--estimate measures a --surfaces run lit by luminaires or "
                                  "emitters, not a daylight one");
        const int rc = daylight(a, mesh, solution, rad_header, grid, mesh_header, argc, argv);
        outputs.commit();
        return rc;
    }
    const rad::Gatherer gatherer(mesh, solution.radiosity, a.options);
    const auto luminaires = rad::solution_luminaires(rad_header, a.rad_path, a.direct_path, mesh,
                                                     a.mesh_path, mesh_header);
    const rad::Box scene_box = rad::bounds(mesh.vertices);
    const auto melanopic =
        melanopic_sources(a, mesh, solution, rad_header, luminaires ? &*luminaires : nullptr);
    if (!a.surfaces_path.empty()) {
        gather_surfaces(a, gatherer, luminaires ? &*luminaires : nullptr, scene_box,
                        rad::metres_per_unit(mesh_header), argc, argv, mesh_header, rad_header,
                        melanopic.get());
        outputs.commit();
        return 0;
    }
    if (!a.grid_text.empty()) check_grid_reach(grid, scene_box);

    // Points from a file or standard input: a folder, a device that never ends a line, a line
    // over 1 MiB or a failed read is an error naming the file and line, never an end.
    std::unique_ptr<rad::LineReader> points;
    if (a.grid_text.empty()) points = std::make_unique<rad::LineReader>(a.points_path);
    std::unique_ptr<SensorSource> source;
    if (!a.grid_text.empty())
        source = std::make_unique<GridSource>(grid);
    else
        source = std::make_unique<LineSource>(*points);
    const std::string source_name = !a.grid_text.empty()    ? "--grid"
                                    : a.points_path.empty() ? "<stdin>"
                                                            : a.points_path;
    rad::RowRange range;
    const auto preamble = sensors_and_preamble(a, grid, mesh_header, rad_header, argc, argv, range);
    const auto start = std::chrono::steady_clock::now();
    GatherRun run(a, gatherer, scene_box, *source, source_name, range,
                  luminaires ? &*luminaires : nullptr, melanopic.get());
    rad::tool::write_output(a.output, [&](std::FILE* out) { run.stream(out, preamble); });
    run.finish();
    if (!a.png.empty())
        rad::write_false_colour_png(a.png, run.grid_lux(), static_cast<int>(grid.nx),
                                    static_cast<int>(grid.nz), "lux",
                                    "illuminance (lux) at y = " + number_text(grid.y), a.lux_max);
    outputs.commit();
    report(a, run, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Final gather: the irradiance (W/m^2, the units of radiosity) arriving at points of a\n"
        "solved scene, or their illuminance in lux. Reads 'x y z dx dy dz' lines (position\n"
        "and the direction the sensor faces; the input of Radiance's rtrace -I) from standard\n"
        "input or --points, and writes one 'r g b' line per point line, in order, streaming.\n"
        "Blank lines and # comments are skipped. Direct light is sampled on the emitters\n"
        "(exact point-to-polygon form factor x the fraction shadow rays see), indirect light\n"
        "with cosine-weighted rays taking the smoothed reflected radiosity where they land."};
    GatherArgs args;
    add_file_options(app, args);
    args.rays_option = rad::tool::add_sensor_gather_options(app, args.options, args.smooth,
                                                            "; daylight: 1024 unless given");
    add_output_options(app, args);
    rad::tool::add_daylight_options(app, args.daylight);
    add_run_options(app, args);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::restart_with_huge_pages(argv);
    return rad::tool::run_tool("rad-gather", [&] { return gather(args, argc, argv); });
}
