#include "radiosity/cli.hpp"

#include "radfmt/container.hpp"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <atomic>
#include <charconv>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <unistd.h>

namespace rad {

std::string command_line(int argc, char** argv) {
    std::string out;
    for (int i = 0; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--threads") {
            ++i;
            continue;
        }
        if (arg.rfind("--threads=", 0) == 0 || arg == "-q" || arg == "--quiet") continue;
        if (i == 0) arg = std::filesystem::path(arg).filename().string();
        const bool plain =
            !arg.empty() && arg.find_first_of(" \t\"'\\$`*?;&|<>()") == std::string::npos;
        if (!out.empty()) out += ' ';
        if (plain) {
            out += arg;
        } else {
            out += '\'';
            for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
            out += '\'';
        }
    }
    return out;
}

std::string tool_version(const std::string& tool) {
    return tool + " " RADIOSITY_VERSION;
}

int run_tool(const char* tool, const std::function<int()>& body) {
    radfmt::install_cleanup_handlers();
    try {
        return body();
    } catch (const CLI::ParseError&) {
        throw; // handled by the caller's CLI11_PARSE
    } catch (const InputError& e) {
        std::cerr << tool << ": error: " << e.what() << '\n';
        return 1;
    } catch (const radfmt::FormatError& e) {
        std::cerr << tool << ": error: " << e.what() << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << tool << ": internal error: out of memory\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << tool << ": internal error: " << e.what() << '\n';
        return 2;
    }
}

ThreadLimit::ThreadLimit(int threads) {
    const int cores = tbb::info::default_concurrency();
    threads_ = threads > 0 ? threads : cores;
    control_ = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     static_cast<std::size_t>(threads_));
}
ThreadLimit::~ThreadLimit() = default;

namespace {
struct ProgressState {
    std::atomic<std::uint64_t> done{0};
    std::mutex mutex;
    std::chrono::steady_clock::time_point last_print;
};
} // namespace

Progress::Progress(std::string label, std::uint64_t total, bool quiet)
    : label_(std::move(label)), total_(total), enabled_(!quiet && ::isatty(2)),
      state_(std::make_shared<ProgressState>()), start_(std::chrono::steady_clock::now()) {}

void Progress::advance(std::uint64_t done_now) {
    auto& s = *static_cast<ProgressState*>(state_.get());
    const auto done = s.done.fetch_add(done_now) + done_now;
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    std::unique_lock lock(s.mutex, std::try_to_lock);
    if (!lock.owns_lock() || now - s.last_print < std::chrono::milliseconds(250)) return;
    s.last_print = now;
    print(done, false);
}

void Progress::finish() {
    if (!enabled_) return;
    auto& s = *static_cast<ProgressState*>(state_.get());
    print(s.done.load(), true);
}

void Progress::print(std::uint64_t done, bool final) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = elapsed > 0 ? done / elapsed : 0;
    const double eta = rate > 0 ? (total_ - done) / rate : 0;
    std::fprintf(stderr, "\r%s: %llu/%llu (%.0f/s, ETA %.1f s)%s", label_.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                 rate, eta, final ? "\n" : "   ");
    std::fflush(stderr);
}

bool parse_number(const std::string& text, double& value) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec == std::errc() && ptr == end) return true;
    // from_chars rejects some spellings stod takes ("nan", "inf", leading space, hex).
    try {
        std::size_t used = 0;
        value = std::stod(text, &used);
        return used == text.size();
    } catch (...) {
        return false;
    }
}

std::uint64_t physical_memory_bytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page_size = ::sysconf(_SC_PAGE_SIZE);
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

std::string human_bytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int unit = 0;
    while (bytes >= 1024 && unit < 4) {
        bytes /= 1024;
        ++unit;
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.1f %s", bytes, units[unit]);
    return text;
}

} // namespace rad
