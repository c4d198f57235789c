// Printing the report's page to PDF with headless Chromium.
#include "radiosity/report_pdf.hpp"

#include "radiosity/error.hpp"

#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fstream>
#include <signal.h>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace rad {
namespace fs = std::filesystem;
namespace {

// The Chromium to run: $RAD_CHROMIUM, or the first of the usual names on PATH.
std::string find_chromium() {
    if (const char* given = std::getenv("RAD_CHROMIUM"); given && *given) {
        if (::access(given, X_OK) != 0)
            throw SystemError(std::string("RAD_CHROMIUM=") + given +
                              " is not a program this user may run: set it to Chromium's path, "
                              "or unset it to use chromium on PATH");
        return given;
    }
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':'))
        for (const char* name : {"chromium", "chromium-browser", "google-chrome"})
            if (::access((fs::path(dir) / name).c_str(), X_OK) == 0) return (fs::path(dir) / name);
    throw SystemError("--pdf prints the page with headless Chromium, and none was found: install "
                      "it (apt-get install chromium) or set RAD_CHROMIUM to its path");
}

// A private temporary folder, removed when done.
struct TempFolder {
    fs::path path;
    TempFolder() {
        std::string pattern = (fs::temp_directory_path() / "rad-report-XXXXXX").string();
        if (!::mkdtemp(pattern.data()))
            throw SystemError("cannot make a temporary folder: " +
                              std::string(std::strerror(errno)));
        path = pattern;
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    ~TempFolder() { remove(); }
    void remove() {
        std::error_code ec;
        if (!path.empty()) fs::remove_all(path, ec);
        path.clear();
    }
};

// A signal that came while Chromium printed (any thread may take it): noted, not acted on.
volatile std::sig_atomic_t g_caught = 0;
extern "C" void note_signal(int s) {
    if (g_caught == 0) g_caught = s;
}

// While alive, SIGINT, SIGTERM and SIGHUP are noted instead of ending the process; the
// handlers before (radfmt's cleanup) come back after.
struct HeldSignals {
    static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction before[3];
    HeldSignals() {
        g_caught = 0;
        struct sigaction note {};
        note.sa_handler = note_signal;
        sigemptyset(&note.sa_mask);
        for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &note, &before[k]);
    }
    HeldSignals(const HeldSignals&) = delete;
    HeldSignals& operator=(const HeldSignals&) = delete;
    ~HeldSignals() {
        for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &before[k], nullptr);
    }
};

// Waits for `pid`; the first signal noted meanwhile is sent on to it (SIGTERM to timeout,
// which passes it to Chromium's process group) and returned once it has gone; 0 when none
// came. `status` receives the child's.
int wait_or_pass_on(pid_t pid, int& status) {
    bool passed = false;
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) return g_caught;
        if (done < 0 && errno != EINTR)
            throw SystemError("waiting for Chromium: " + std::string(std::strerror(errno)));
        if (g_caught != 0 && !passed) {
            ::kill(pid, SIGTERM);
            passed = true;
        }
        const timespec tick{0, 20'000'000};
        ::nanosleep(&tick, nullptr);
    }
}

std::string tail_of(const fs::path& log) {
    std::ifstream in(log);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text.size() > 600 ? "..." + text.substr(text.size() - 600) : text;
}

// A file:// URL for `path`, every byte but the unreserved ones percent-encoded: a '#' or '%'
// in TMPDIR made the URL point elsewhere (a '#' at the folder above, whose listing became the
// PDF).
std::string file_url(const fs::path& path) {
    static const char* kHex = "0123456789ABCDEF";
    std::string url = "file://";
    for (const unsigned char c : path.string()) {
        if (std::isalnum(c) || c == '/' || c == '-' || c == '.' || c == '_' || c == '~') {
            url += static_cast<char>(c);
        } else {
            url += '%';
            url += kHex[c >> 4];
            url += kHex[c & 15];
        }
    }
    return url;
}

// The file starts as a PDF does.
bool looks_like_pdf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char head[5] = {};
    in.read(head, 5);
    return in.gcount() == 5 && std::string(head, 5) == "%PDF-";
}

} // namespace

void print_pdf(const std::string& html, const fs::path& pdf, int timeout_seconds) {
    const auto chromium = find_chromium();
    TempFolder temp;
    const auto page = temp.path / "report.html";
    {
        std::ofstream out(page, std::ios::binary);
        out << html;
        if (!out) throw SystemError(page.string() + ": cannot write the page to print");
    }
    const auto log = temp.path / "chromium.log";
    std::vector<std::string> args = {
        "timeout", std::to_string(timeout_seconds), chromium, "--headless", "--no-sandbox",
        "--disable-gpu", "--no-first-run", "--disable-extensions",
        // Nothing but the page: no update, account, sync or
        // metrics traffic from a browser printing a local file.
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--disable-default-apps", "--disable-domain-reliability",
        "--disable-client-side-phishing-detection", "--disable-breakpad",
        "--no-default-browser-check", "--metrics-recording-only",
        "--user-data-dir=" + (temp.path / "profile").string(), "--no-pdf-header-footer",
        "--print-to-pdf=" + fs::absolute(pdf).string(), file_url(page)};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    // Ctrl-C, a kill or a hang-up while Chromium prints must end Chromium too (`timeout`
    // keeps it in a process group of its own, which the terminal's signal never reaches) and
    // leave no file behind: a signal that comes is passed on to it, and raised here once it
    // has gone.
    int status = 0, caught = 0;
    {
        HeldSignals held;
        pid_t pid = 0;
        const int spawned = posix_spawnp(&pid, "timeout", &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        if (spawned != 0)
            throw SystemError("cannot run " + chromium + ": " + std::strerror(spawned));
        caught = wait_or_pass_on(pid, status);
    }
    if (caught != 0) {
        // Chromium has gone; the temporary folder goes now, the partial PDF with the handler
        // the signal runs (radfmt's cleanup), which ends the process as the signal would.
        temp.remove();
        ::raise(caught);
    }
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    std::error_code ec;
    if (ok && fs::exists(pdf, ec) && !looks_like_pdf(pdf))
        throw SystemError(chromium +
                          " wrote a file that is not a PDF (no %PDF- at its start) "
                          "printing the page; its output: " +
                          tail_of(log));
    if (!ok || !fs::exists(pdf, ec) || fs::file_size(pdf, ec) == 0) {
        const bool timed_out = WIFEXITED(status) && WEXITSTATUS(status) == 124;
        throw SystemError(chromium +
                          (timed_out ? " took over " + std::to_string(timeout_seconds) + " s"
                                     : std::string(" failed")) +
                          " printing the page to PDF; its output: " + tail_of(log));
    }
}

} // namespace rad
