#include "radiosity/huge_pages.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string_view>
#include <sys/stat.h>
#include <unistd.h>

namespace rad {

namespace {

constexpr std::string_view kTunable = "glibc.malloc.hugetlb";

// The kernel's policy, "always", "madvise" or "never" (empty when it cannot be read).
std::string kernel_policy() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(in, line);
    const auto open = line.find('['), close = line.find(']');
    if (open == std::string::npos || close == std::string::npos || close < open) return "";
    return line.substr(open + 1, close - open - 1);
}

bool opted_out() {
    const char* value = std::getenv("RADIOSITY_HUGE_PAGES");
    return value && std::string_view(value) == "0";
}

// Why the process was not restarted for huge pages, when it was not (for --timings and -v).
std::string& not_restarted() {
    static std::string why;
    return why;
}

// The file `argv0` names: itself when it has a slash, else the first match on PATH.
std::string named_file(const std::string& argv0) {
    if (argv0.find('/') != std::string::npos) return argv0;
    const char* path = std::getenv("PATH");
    std::string_view dirs = path ? path : "";
    while (!dirs.empty()) {
        const auto colon = dirs.find(':');
        const std::string dir(dirs.substr(0, colon));
        const auto candidate = (dir.empty() ? "." : dir) + "/" + argv0;
        if (access(candidate.c_str(), X_OK) == 0) return candidate;
        dirs = colon == std::string_view::npos ? "" : dirs.substr(colon + 1);
    }
    return "";
}

// The process image (/proc/self/exe) is the program argv[0] names: not a loader or a tool
// running it (ld.so TOOL, valgrind TOOL), which /proc/self/exe would name instead, and which
// exec'd with the tool's arguments would run something else.
bool image_is_the_program(const char* argv0) {
    struct stat self {
    }, named{};
    const auto file = argv0 ? named_file(argv0) : "";
    return !file.empty() && stat("/proc/self/exe", &self) == 0 && stat(file.c_str(), &named) == 0 &&
           self.st_dev == named.st_dev && self.st_ino == named.st_ino;
}

std::string tunables() {
    const char* value = std::getenv("GLIBC_TUNABLES");
    return value ? value : "";
}

} // namespace

void restart_with_huge_pages(char** argv) {
    const auto current = tunables();
    if (opted_out() || current.find(kTunable) != std::string::npos) return;
    const auto policy = kernel_policy();
    if (policy.empty() || policy == "never") return;
    if (!image_is_the_program(argv[0])) {
        not_restarted() = "not restarted for huge pages: the process image is not the program "
                          "itself (run through a loader or a tool such as valgrind)";
        return;
    }
    const auto wanted = (current.empty() ? "" : current + ":") + std::string(kTunable) + "=1";
    if (setenv("GLIBC_TUNABLES", wanted.c_str(), 1) != 0) return;
    execv("/proc/self/exe", argv);
    // Still here: the restart failed; go on with the pages we have.
    if (current.empty())
        unsetenv("GLIBC_TUNABLES");
    else
        setenv("GLIBC_TUNABLES", current.c_str(), 1);
}

std::string huge_pages_state() {
    std::string state = "4 KiB pages (GLIBC_TUNABLES sets " + std::string(kTunable) + ")";
    const auto policy = kernel_policy();
    if (tunables().find(std::string(kTunable) + "=1") != std::string::npos)
        state = "transparent huge pages asked for (" + std::string(kTunable) + "=1)";
    else if (!not_restarted().empty())
        state = "4 KiB pages (" + not_restarted() + ")";
    else if (opted_out())
        state = "4 KiB pages (RADIOSITY_HUGE_PAGES=0)";
    else if (policy.empty() || policy == "never")
        state = "4 KiB pages (the kernel has transparent huge pages off)";
    std::ifstream in("/proc/self/smaps_rollup");
    for (std::string line; std::getline(in, line);) {
        long kib = 0;
        if (std::sscanf(line.c_str(), "AnonHugePages: %ld kB", &kib) == 1) {
            char text[64];
            std::snprintf(text, sizeof text, ", %.1f MiB in them now", kib / 1024.0);
            state += text;
        }
    }
    return state;
}

} // namespace rad
