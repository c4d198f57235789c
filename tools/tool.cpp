#include "tool.hpp"

#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <poll.h>
#include <unistd.h>

namespace rad::tool {

int parse_arguments(CLI::App& app, int argc, char** argv) {
    // A reader that goes away is a normal end from the first byte on, --help included
    // (`rad-mesh --help | grep -q x` must not die of SIGPIPE when grep stops reading).
    std::signal(SIGPIPE, SIG_IGN);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 1;
    }
    // Outputs record the command line in their header (twice: as the command and in the
    // provenance chain), and readers accept at most kMaxHeaderBytes: refuse before any work
    // rather than after it, when the writer would.
    const auto command = radfmt::command_line(argc, argv);
    if (command.size() > radfmt::kMaxHeaderBytes / 2) {
        std::cerr << std::filesystem::path(argc > 0 ? argv[0] : "radiosity").filename().string()
                  << ": error: the command line is " << command.size()
                  << " bytes; outputs record it in a header that readers "
                  << "accept up to " << radfmt::kMaxHeaderBytes
                  << " bytes: pass fewer or shorter arguments\n";
        return 1;
    }
    return -1;
}

int run_tool(const char* tool, const std::function<int()>& body) {
    radfmt::install_cleanup_handlers();
    // A reader that goes away (rad-info --csv | head) is a normal end, not a crash: write
    // errors come back as EPIPE instead of killing the process.
    std::signal(SIGPIPE, SIG_IGN);
    try {
        const int rc = body();
        // Standard output written out, the C++ and the C streams both: a write that failed
        // (a full disk, /dev/full) cut what the tool printed, a system error; a reader that
        // went away is a normal end.
        errno = 0;
        std::cout.flush();
        const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
        const int error = errno;
        if (!failed || stdout_reader_gone()) return rc;
        std::cerr << tool << ": system error: cannot write to standard output"
                  << (error ? std::string(" (") + std::strerror(error) + ")" : std::string())
                  << ": what it printed is cut short\n";
        return 2;
    } catch (const InputError& e) {
        std::cerr << tool << ": error: " << e.what() << '\n';
        return 1;
    } catch (const radfmt::FormatError& e) {
        std::cerr << tool << ": error: " << e.what() << '\n';
        return 1;
    } catch (const SystemError& e) {
        std::cerr << tool << ": system error: " << e.what() << '\n';
        return 2;
    } catch (const radfmt::WriteError& e) {
        std::cerr << tool << ": system error: " << e.what() << '\n';
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << tool << ": system error: out of memory\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << tool << ": internal error: " << e.what() << '\n';
        return 3;
    }
}

bool stdout_reader_gone() {
    // The write end of a pipe whose read end is closed polls as an error.
    pollfd out{STDOUT_FILENO, POLLOUT, 0};
    return ::poll(&out, 1, 0) == 1 && (out.revents & POLLERR) != 0;
}

CLI::Validator finite_range(double lo, double hi) {
    char description[96];
    std::snprintf(description, sizeof description, "NUMBER in [%g, %g]", lo, hi);
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            double value = 0;
            if (!parse_number(text, value) || value < lo || value > hi) {
                char message[160];
                std::snprintf(message, sizeof message, "'%s' is not a number in [%g, %g]",
                              text.c_str(), lo, hi);
                return message;
            }
            return {};
        },
        description);
}

std::string lower_extension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (auto& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

std::string one_of(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return out;
}

std::uint64_t parse_size(const std::string& text, const std::string& option) {
    std::size_t split = 0;
    while (split < text.size() && (std::isdigit(static_cast<unsigned char>(text[split])) ||
                                   text[split] == '.' || text[split] == 'e' || text[split] == '+'))
        ++split;
    double value = 0;
    if (!parse_number(text.substr(0, split), value))
        throw InputError(option + ": '" + text + "' is not a size (e.g. 8G, 512M)");
    const std::string unit = text.substr(split);
    double scale = 1;
    if (unit == "K" || unit == "KiB" || unit == "k")
        scale = 1024.0;
    else if (unit == "M" || unit == "MiB")
        scale = 1024.0 * 1024;
    else if (unit == "G" || unit == "GiB")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "T" || unit == "TiB")
        scale = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty() && unit != "B")
        throw InputError(option + ": unknown unit '" + unit + "' in '" + text +
                         "' (use K, M, G or T)");
    const double bytes = value * scale;
    if (!(bytes >= 1) || bytes > 1e18)
        throw InputError(option + ": '" + text + "' must be between 1 B and 1e18 B");
    return static_cast<std::uint64_t>(bytes);
}

namespace {
namespace fs = std::filesystem;

// The same file, whether or not it exists yet, however it is spelled.
bool same_file(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(fs::absolute(a), ec) == fs::weakly_canonical(fs::absolute(b), ec);
}

// Whether `path` is a name `pattern` (with one %d) expands to for a number it writes.
bool matches_pattern(const NumberedOutput& output, const std::string& path) {
    const auto& pattern = output.pattern;
    const auto at = pattern.find("%d");
    if (at == std::string::npos) return same_file(pattern, path);
    std::error_code ec;
    const auto canonical = [&](const std::string& p) {
        return fs::weakly_canonical(fs::absolute(p), ec).string();
    };
    // Expand with a marker that survives canonicalisation, then match digits in its place.
    const std::string marker = "\x01radiosity-iteration\x01";
    const auto expanded = canonical(pattern.substr(0, at) + marker + pattern.substr(at + 2));
    const auto where = expanded.find(marker);
    if (where == std::string::npos) return false;
    const auto prefix = expanded.substr(0, where), suffix = expanded.substr(where + marker.size());
    const auto candidate = canonical(path);
    if (candidate.size() <= prefix.size() + suffix.size()) return false;
    if (candidate.compare(0, prefix.size(), prefix) != 0) return false;
    if (candidate.compare(candidate.size() - suffix.size(), suffix.size(), suffix) != 0)
        return false;
    const auto digits =
        candidate.substr(prefix.size(), candidate.size() - prefix.size() - suffix.size());
    if (digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos ||
        (digits.size() > 1 && digits[0] == '0'))
        return false;
    return !output.writes || output.writes(std::stol(digits));
}
} // namespace

std::uint64_t memory_limit(const std::string& max_memory) {
    return max_memory.empty()
               ? static_cast<std::uint64_t>(kDefaultMemoryShare * double(job_memory_bytes()))
               : parse_size(max_memory, "--max-memory");
}

std::string memory_limit_text(const std::string& max_memory) {
    if (!max_memory.empty()) return "--max-memory " + human_bytes(double(memory_limit(max_memory)));
    std::string source;
    const auto bytes = job_memory_bytes(&source);
    return "--max-memory's default " + human_bytes(kDefaultMemoryShare * double(bytes)) + " (" +
           std::to_string(std::lround(100 * kDefaultMemoryShare)) + "% of " + source + ", " +
           human_bytes(double(bytes)) + ")";
}

void check_outputs(const std::vector<std::string>& inputs,
                   const std::vector<std::pair<std::string, std::string>>& outputs,
                   const std::vector<NumberedOutput>& patterns) {
    for (std::size_t k = 0; k < outputs.size(); ++k) {
        const auto& [option, path] = outputs[k];
        if (path.empty()) continue;
        const fs::path target(path);
        std::error_code ec;
        const auto status = fs::status(target, ec);
        if (fs::is_directory(status))
            throw InputError(option + " " + path + " is a folder: give a file name in it");
        const bool special = fs::exists(status) && !fs::is_regular_file(status);
        const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
        if (!special && !fs::is_directory(folder))
            throw InputError(option + " " + path + ": the folder '" + folder.string() +
                             "' does not exist (nothing was computed)");
        if (!special && ::access(folder.c_str(), W_OK | X_OK) != 0)
            throw SystemError(option + " " + path + ": cannot write in the folder '" +
                              folder.string() + "': " + std::strerror(errno) +
                              " (nothing was computed)");
        for (const auto& input : inputs)
            if (!input.empty() && same_file(input, path))
                throw InputError(option + " " + path +
                                 " is also an input of this run: it would be overwritten");
        for (std::size_t j = 0; j < k; ++j)
            if (!outputs[j].second.empty() && same_file(outputs[j].second, path))
                throw InputError(option + " and " + outputs[j].first + " both write " + path);
    }
    for (const auto& numbered : patterns) {
        const auto& [option, pattern, writes] = numbered;
        if (pattern.empty()) continue;
        const fs::path folder =
            fs::path(pattern).has_parent_path() ? fs::path(pattern).parent_path() : fs::path(".");
        if (!fs::is_directory(folder))
            throw InputError(option + " " + pattern + ": the folder '" + folder.string() +
                             "' does not exist (nothing was computed)");
        for (const auto& input : inputs)
            if (!input.empty() && matches_pattern(numbered, input))
                throw InputError(option + " " + pattern + " would overwrite the input " + input);
        for (const auto& [other, path] : outputs)
            if (!path.empty() && matches_pattern(numbered, path))
                throw InputError(option + " " + pattern + " would overwrite " + other + " " + path);
    }
}

void add_sky_options(CLI::App& app, SkyChoice& choice, const std::string& what) {
    app.add_option("--sky", choice.sky,
                   what + ": uniform[:L] (cd/m^2), cie-overcast[:LUX], cie:TYPE[:LUX] (the 15 CIE "
                          "standard general skies), perez:DNI,DHI (W/m^2), clear (CIE 12 with the "
                          "IES clear-sky daylight availability and the sun's beam), "
                          "partly-cloudy (CIE 7, the IES partly cloudy availability), overcast "
                          "(CIE 1, the IES overcast availability), epw:FILE (the weather file's "
                          "record of the hour --date and --time fall in: Perez's sky as a year "
                          "takes it); LUX is the sky's horizontal illuminance (default 10000)");
    app.add_option("--sun", choice.sun,
                   "The sun for --sky cie:TYPE, perez, clear, partly-cloudy or overcast: ALT,AZ "
                   "in degrees (azimuth "
                   "from north towards east)");
    app.add_option("--date", choice.date, "The sun by date and time: YYYY-MM-DD (with --time)");
    app.add_option("--time", choice.time, "HH:MM, local standard time (with --date)");
    app.add_option("--location", choice.location,
                   "LAT,LON,TZ[,ELEVATION] for --date (degrees north, degrees east, hours east "
                   "of UTC, m)");
    app.add_option("--ground", choice.ground,
                   "The ground's reflectance below the horizon (its luminance: this x the "
                   "global horizontal illuminance / pi)")
        ->capture_default_str()
        ->check(finite_range(0, 1));
}

void write_output(const std::string& output, const std::function<void(std::FILE*)>& write) {
    if (output.empty()) {
        write(stdout); // run_tool checks what reached stdout
        return;
    }
    radfmt::write_atomically(output, [&](const std::filesystem::path& temp) {
        std::FILE* out = std::fopen(temp.c_str(), "w");
        if (!out)
            throw rad::SystemError(output + ": cannot open for writing: " + std::strerror(errno));
        try {
            write(out);
        } catch (...) {
            std::fclose(out);
            throw;
        }
        if (std::fclose(out) != 0)
            throw rad::SystemError(output + ": cannot write: " + std::strerror(errno));
    });
}

std::string about(double seconds) {
    char text[64];
    if (seconds < 10)
        std::snprintf(text, sizeof text, "about %.1f s", seconds);
    else if (seconds < 300) // whole minutes would be a quarter off at 90 s
        std::snprintf(text, sizeof text, "about %.0f s", seconds);
    else if (seconds < 5400)
        std::snprintf(text, sizeof text, "about %.0f min", seconds / 60);
    else
        std::snprintf(text, sizeof text, "about %.1f h", seconds / 3600);
    return text;
}

void say_sensors_estimate(const char* tool, const SensorsEstimate& estimate, bool always) {
    if (!always && estimate.seconds < kSayEstimateSeconds) return;
    std::fprintf(stderr,
                 "%s: %llu sensor(s) on %zu surface(s): %s on %u thread(s) (measured on the "
                 "first %llu)\n",
                 tool, static_cast<unsigned long long>(estimate.sensors), estimate.surfaces,
                 about(estimate.seconds).c_str(), estimate.threads,
                 static_cast<unsigned long long>(estimate.measured));
}

std::string error_suffix(double error) {
    if (!std::isfinite(error)) return "";
    char text[48];
    std::snprintf(text, sizeof text, " ± %.2g", error);
    return text;
}

void warn_facing_too_close(const char* tool, const CalcSurface& surface, double distance_m) {
    if (!std::isfinite(distance_m)) return;
    std::fprintf(stderr,
                 "%s: warning: %s: surface '%s' faces a surface %.3g m in front of its points: "
                 "they read the light leaving that surface, not the light falling on the place (a "
                 "wall's or ceiling's surface given facing into it?); give u and v the other way "
                 "round so it faces the room, or move it\n",
                 tool, surface.where.str().c_str(), surface.name.c_str(), distance_m);
}

void warn_at_budget(const char* what, long count, int max_rays, double accuracy,
                    const std::string& names) {
    if (count == 0) return;
    std::fprintf(stderr,
                 "rad-gather: warning: %ld %s stopped at --max-rays %d before a standard error "
                 "of %g%%: %s%s (raise --max-rays, or accept the error written with --error)\n",
                 count, what, max_rays, 100 * accuracy, names.c_str(), count > 3 ? ", ..." : "");
}

void add_accuracy_options(CLI::App& app, GatherOptions& options) {
    app.add_option("--accuracy", options.accuracy,
                   "Keep sampling each point until the standard error of its illuminance is at "
                   "most this share of it (0.01: 1%), or --max-rays is reached: the rays and "
                   "shadow rays given are the first round, and more are added where the "
                   "variance is, direct or indirect. 0: exactly the rays given, whatever the "
                   "error")
        ->capture_default_str()
        ->check(finite_range(0, 1));
    app.add_option("--max-rays", options.max_rays,
                   "--accuracy: at most this many indirect rays per point, and as many shadow "
                   "rays; points that stop here are counted and named")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000000));
    app.add_option("--batches", options.batches,
                   "The rays of a point are cast in this many independent batches; their "
                   "spread is the point's standard error (1: none estimated)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1024));
}

CLI::Option* add_sensor_gather_options(CLI::App& app, GatherOptions& options, std::string& smooth,
                                       const std::string& rays_help) {
    auto* rays = app.add_option("--rays", options.rays,
                                "Indirect light: cosine-weighted rays per point (0: direct "
                                "light only" +
                                    rays_help + ")")
                     ->capture_default_str()
                     ->check(CLI::Range(0, 1000000));
    app.add_option("--shadow-rays", options.shadow_rays,
                   "Direct light: shadow rays per point for the lights' visible fractions "
                   "(emitting patches, and patches lit so brightly that rays landing on them "
                   "would be fireflies), shared by what each contributes; lights too faint "
                   "for one each share theirs (--exact: per patch); 0: no shadows")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    add_accuracy_options(app, options);
    app.add_flag("--exact", options.exact,
                 "Indirect light as the exact point-to-polygon sum over every patch (with "
                 "shadow rays for visibility) instead of rays: no ray noise, cost grows with "
                 "the patches; for small scenes");
    app.add_option("--smooth", smooth,
                   "How the radiosity where a ray lands is interpolated: crease, area, average "
                   "or flat (as rad-shade), then scaled so that each patch keeps its solved "
                   "mean")
        ->capture_default_str();
    app.add_option("--crease-angle", options.crease_deg, "crease: largest angle smoothed over")
        ->capture_default_str()
        ->check(finite_range(0, 180));
    return rays;
}

Sky sky_of(const SkyChoice& choice, const std::string& epw, const SkyFrame& frame) {
    if (choice.sky.rfind("epw:", 0) == 0) {
        if (!choice.sun.empty() || !choice.location.empty())
            throw InputError("--sky epw:FILE takes the place and the sun from the weather file: "
                             "not with --sun or --location");
        return weather_file_sky(choice.sky.substr(4), choice.date, choice.time, frame,
                                choice.ground);
    }
    int day = 172;
    const auto sun = sun_from({choice.sun, choice.date, choice.time, choice.location, epw}, day);
    return parse_sky(choice.sky, sun ? &*sun : nullptr, day, frame, choice.ground);
}

} // namespace rad::tool
