// Progress on stderr for long work (only when stderr is a terminal) and thread limits.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

namespace rad {

// Limits TBB to `threads` workers for the lifetime of the object (0: all cores).
class ThreadLimit {
  public:
    explicit ThreadLimit(int threads);
    ~ThreadLimit();
    int threads() const { return threads_; }
    static int max_threads(); // the most ThreadLimit accepts: a sane bound over the cores

  private:
    std::shared_ptr<void> control_;
    int threads_ = 0;
};

// Items-done progress with rate and ETA, printed to stderr only when it is a terminal.
class Progress {
  public:
    Progress(std::string label, std::uint64_t total, bool quiet); // total 0: unknown
    void advance(std::uint64_t done_now);                         // thread-safe
    void finish();

  private:
    void print(std::uint64_t done, bool final);
    std::string label_;
    std::uint64_t total_;
    bool enabled_;
    std::shared_ptr<void> state_;
    std::chrono::steady_clock::time_point start_;
};

} // namespace rad
