// What every tool's main shares (tools only: the library knows nothing of CLI11): argument
// parsing with the house exit codes, and running a tool body with errors mapped to them.
#pragma once
#include "common_options.hpp"
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/sky.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>

#include <functional>
#include <string>
#include <vector>

namespace rad::tool {

// Parses arguments; returns -1 to go on, or the exit code to return at once (0 after
// --help, 1 for a usage error).
int parse_arguments(CLI::App& app, int argc, char** argv);

// Runs a tool body: prints "<tool>: error: ..." and returns 1 for bad input or usage
// (InputError, FormatError), 2 for system failures (SystemError, WriteError, out of memory,
// a closed output pipe is not one: it ends the tool quietly with 0), 3 for anything else.
int run_tool(const char* tool, const std::function<int()>& body);

// A validator for real-valued options: the whole value is a finite decimal number (the
// library's one grammar) within [lo, hi]. CLI::Range lets NaN through (every comparison
// with NaN is false), so real-valued options use this instead.
CLI::Validator finite_range(double lo, double hi);

// Whether standard output is a pipe whose reader has gone (`rad-info --csv | head`): a
// normal end for every tool, not a failed write.
bool stdout_reader_gone();

// Outputs named by a pattern with one %d (snapshots): the option, the pattern, and which
// numbers it will write (empty: any).
struct NumberedOutput {
    std::string option, pattern;
    std::function<bool(long)> writes;
};

// Checks, before any work, that every output can be written where it is going and does not
// overwrite an input or another output of the same run. `inputs` are paths; `outputs` are
// (option, path) pairs, empty paths skipped; numbered outputs (snapshots) must not expand
// to an input or an output for a number they write.
// Throws InputError naming the options (SystemError for a folder we may not write in).
void check_outputs(const std::vector<std::string>& inputs,
                   const std::vector<std::pair<std::string, std::string>>& outputs,
                   const std::vector<NumberedOutput>& patterns = {});

// The limit --max-memory gives (parse_size), or 80% of what the job may use when it is empty
// (rad::job_memory_bytes: physical memory, a cgroup's limit, ulimit -v).
std::uint64_t memory_limit(const std::string& max_memory);
// "--max-memory 100.0 MiB", or "--max-memory's default 1.2 GiB (80% of the address-space
// limit (ulimit -v), 1.5 GiB)": for messages refusing work over the limit.
std::string memory_limit_text(const std::string& max_memory);

// A path's extension in lower case (".png"): what format a name says.
std::string lower_extension(const std::string& path);

// "name1, name2 or name3" for help texts.
std::string one_of(const std::vector<std::string>& names);

// "8G", "512M", "100K", "1T" (binary units) or plain bytes; throws InputError naming
// `option` otherwise.
std::uint64_t parse_size(const std::string& text, const std::string& option);

// Runs `write` on stdout (output empty), or on a temporary file that becomes `output` when it
// is all there (SystemError, with the system's reason, when it cannot be written).
void write_output(const std::string& output, const std::function<void(std::FILE*)>& write);

// Below this, a run is over before an estimate of its time would matter.
inline constexpr double kSayEstimateSeconds = 10;
// A time as an estimate says it: "about 4.2 s", "about 75 s", "about 12 min", "about 1.5 h".
std::string about(double seconds);

// rad-gather's and rad-report's word on a calculation-surfaces run's time, on stderr, when it
// is `always` asked for or over kSayEstimateSeconds: "TOOL: N sensor(s) on M surface(s): about
// T on K thread(s) (measured on the first S)".
void say_sensors_estimate(const char* tool, const SensorsEstimate& estimate, bool always);

// " ± 0.012": a printed figure's standard error to two digits; "" when it is not known.
std::string error_suffix(double error);

// `tool`'s warning (nothing when `distance_m` is NaN) that `surface`'s points face another
// surface `distance_m` in front of them (GatheredSurface::facing_distance_m), at its line.
void warn_facing_too_close(const char* tool, const CalcSurface& surface, double distance_m);

// The warning that `count` points (`what`: "point(s)", "sensor(s)") stopped at `max_rays`
// before the standard error `accuracy` asked for, the first few named in `names` (nothing when
// none did).
void warn_at_budget(const char* what, long count, int max_rays, double accuracy,
                    const std::string& names);

// --accuracy, --max-rays and --batches: the error bar and sampling to a stated accuracy.
void add_accuracy_options(CLI::App& app, GatherOptions& options);
// How a final gather at sensors is made (rad-gather, rad-report, so that both give the same
// numbers): --rays, --shadow-rays, --exact, --smooth, --crease-angle (--seed is common).
// `rays_help` ends --rays' help. Returns the --rays option (whether it was given).
CLI::Option* add_sensor_gather_options(CLI::App& app, GatherOptions& options, std::string& smooth,
                                       const std::string& rays_help);

// A sky at an instant as a command line names it (rad-gather, rad-shade): --sky, --sun,
// --date, --time, --location, --ground. `what` says what the sky is for, in --sky's help.
struct SkyChoice {
    std::string sky, sun, date, time, location;
    double ground = 0.2;
};
void add_sky_options(CLI::App& app, SkyChoice& choice, const std::string& what);
// The sky `choice` names, in `frame`; `epw` (may be empty) gives the place for --date.
Sky sky_of(const SkyChoice& choice, const std::string& epw, const SkyFrame& frame);

} // namespace rad::tool
