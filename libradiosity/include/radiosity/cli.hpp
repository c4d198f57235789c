// What every tool's main shares: error handling with the house exit codes, the command
// line for provenance, thread control and progress on a terminal.
#pragma once
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace rad {

// Bad input or usage: exit code 1. Anything else escaping a tool is internal: exit code 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The command line as recorded in provenance headers. Options that cannot change a result
// (--threads N, -q/--quiet) are left out, so outputs are byte-identical at any thread count.
std::string command_line(int argc, char** argv);
std::string tool_version(const std::string& tool);

// Runs a tool body, mapping exceptions to messages on stderr and exit codes.
int run_tool(const char* tool, const std::function<int()>& body);

// Limits TBB to `threads` workers for the lifetime of the object (0: all cores).
class ThreadLimit {
  public:
    explicit ThreadLimit(int threads);
    ~ThreadLimit();
    int threads() const { return threads_; }

  private:
    std::shared_ptr<void> control_;
    int threads_ = 0;
};

// Rows-done progress with rate and ETA, printed to stderr only when it is a terminal.
class Progress {
  public:
    Progress(std::string label, std::uint64_t total, bool quiet);
    void advance(std::uint64_t done_now); // thread-safe
    void finish();

  private:
    void print(std::uint64_t done, bool final);
    std::string label_;
    std::uint64_t total_;
    bool enabled_;
    std::shared_ptr<void> state_;
    std::chrono::steady_clock::time_point start_;
};

// Parses arguments; returns -1 to go on, or the exit code to return at once (0 after
// --help, 1 for a usage error, as the house conventions require).
inline int parse_arguments(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 1;
    }
    return -1;
}

// Parses the whole of `text` as a number (nan and inf spellings included, so callers can
// report them); false when it is not one.
bool parse_number(const std::string& text, double& value);

std::uint64_t physical_memory_bytes();
std::string human_bytes(double bytes);

} // namespace rad
