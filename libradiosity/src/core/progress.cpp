#include "radiosity/progress.hpp"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <unistd.h>

namespace rad {

int ThreadLimit::max_threads() {
    return 64 * std::max(1, tbb::info::default_concurrency());
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
    if (total_ == 0) { // an unknown total (a stream): the count and the rate
        std::fprintf(stderr, "\r%s: %llu (%.0f/s)%s", label_.c_str(),
                     static_cast<unsigned long long>(done), rate, final ? "\n" : "   ");
        std::fflush(stderr);
        return;
    }
    const double eta = rate > 0 ? (total_ - done) / rate : 0;
    std::fprintf(stderr, "\r%s: %llu/%llu (%.0f/s, ETA %.1f s)%s", label_.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                 rate, eta, final ? "\n" : "   ");
    std::fflush(stderr);
}

} // namespace rad
