// The stage a long run is in, for a person watching (on stderr when it is a terminal) and,
// with `timings`, each stage's wall time and the process's peak memory so far, for finding
// where a large input's time and memory go.
#pragma once
#include <chrono>
#include <string>

namespace rad {

class StageLog {
  public:
    // `tool` prefixes each line ("rad-mesh"); `quiet` silences the terminal display only.
    StageLog(std::string tool, bool quiet, bool timings);
    StageLog(const StageLog&) = delete;
    StageLog& operator=(const StageLog&) = delete;
    ~StageLog();
    void begin(std::string stage); // ends the stage before it
    void fraction(double done);    // how far the stage is (0..1): shown at most 4 times a second
    void finish();                 // ends the last stage, clears the terminal line

  private:
    void end_stage();
    void show(double done);
    std::string tool_;
    bool terminal_;
    bool timings_;
    std::string stage_;
    std::chrono::steady_clock::time_point stage_start_, last_shown_;
    bool shown_ = false;
};

// The process's peak resident memory so far, in bytes (getrusage).
std::size_t peak_memory_bytes();

// Reports a stage's progress to a StageLog that may be absent.
inline void begin_stage(StageLog* log, std::string stage) {
    if (log) log->begin(std::move(stage));
}
inline void stage_fraction(StageLog* log, double done) {
    if (log) log->fraction(done);
}

} // namespace rad
