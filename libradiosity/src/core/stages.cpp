#include "radiosity/stages.hpp"

#include <cstdio>
#include <sys/resource.h>
#include <unistd.h>

namespace rad {

std::size_t peak_memory_bytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return static_cast<std::size_t>(usage.ru_maxrss) * 1024; // Linux gives KiB
}

StageLog::StageLog(std::string tool, bool quiet, bool timings)
    : tool_(std::move(tool)), terminal_(!quiet && ::isatty(2)), timings_(timings) {}

StageLog::~StageLog() {
    finish();
}

void StageLog::begin(std::string stage) {
    end_stage();
    stage_ = std::move(stage);
    stage_start_ = std::chrono::steady_clock::now();
    last_shown_ = stage_start_;
    show(-1);
}

void StageLog::fraction(double done) {
    if (!terminal_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_shown_ < std::chrono::milliseconds(250)) return;
    last_shown_ = now;
    show(done);
}

void StageLog::finish() {
    end_stage();
    stage_.clear();
}

void StageLog::end_stage() {
    if (stage_.empty()) return;
    if (terminal_ && shown_) {
        std::fprintf(stderr, "\r\033[K");
        shown_ = false;
    }
    if (timings_) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
        std::fprintf(stderr, "%s: timing: %-22s %8.2f s, peak memory %7.1f MiB\n", tool_.c_str(),
                     stage_.c_str(), seconds, peak_memory_bytes() / 1048576.0);
    }
    std::fflush(stderr);
}

void StageLog::show(double done) {
    if (!terminal_) return;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
    if (done >= 0)
        std::fprintf(stderr, "\r\033[K%s: %s %3.0f%% (%.0f s)", tool_.c_str(), stage_.c_str(),
                     100 * done, seconds);
    else
        std::fprintf(stderr, "\r\033[K%s: %s", tool_.c_str(), stage_.c_str());
    std::fflush(stderr);
    shown_ = true;
}

} // namespace rad
