// An import in a forked child: limits set, the import run on a thread with a large stack,
// its Scene sent back through a pipe (import/scene_wire.hpp) while the parent waits with a
// deadline.
#include "import/isolated.hpp"

#include "import/scene_wire.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"

#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <new>

namespace rad::import {

namespace {
// The child's first byte says what follows.
enum Status : char { kScene = 'S', kInput = 'I', kMemory = 'M', kInternal = 'X' };

struct Job {
    const std::function<Scene(SceneReport&)>* import;
    std::string out;
};

void* run_job(void* data) {
    auto& job = *static_cast<Job*>(data);
    try {
        SceneReport report;
        const Scene scene = (*job.import)(report);
        job.out = char(kScene) + encode_scene(scene, report);
    } catch (const InputError& e) {
        job.out = char(kInput) + std::string(e.what());
    } catch (const std::bad_alloc&) {
        job.out = char(kMemory);
    } catch (const std::exception& e) {
        job.out = char(kInternal) + std::string(e.what());
    } catch (...) {
        job.out = char(kInternal) + std::string("an exception of unknown type");
    }
    return nullptr;
}

bool write_all(int fd, const std::string& bytes) {
    std::size_t at = 0;
    while (at < bytes.size()) {
        const auto n = ::write(fd, bytes.data() + at, bytes.size() - at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        at += static_cast<std::size_t>(n);
    }
    return true;
}

// The child: limits, then the import on a thread with its own large stack (deep nesting in
// a file recurses in the importer), the answer written to `fd`. Never returns.
[[noreturn]] void child(int fd, const ImportLimits& limits,
                        const std::function<Scene(SceneReport&)>& import) {
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    std::size_t stack = limits.stack_bytes;
#if !defined(__SANITIZE_ADDRESS__) // its shadow memory is address space already taken
    if (limits.memory_bytes > 0) {
        const rlimit memory{limits.memory_bytes, limits.memory_bytes};
        ::setrlimit(RLIMIT_AS, &memory);
        stack = std::min<std::size_t>(stack, limits.memory_bytes / 4);
    }
#endif
    Job job{&import, {}};
    pthread_attr_t attributes;
    pthread_t thread;
    const bool threaded = pthread_attr_init(&attributes) == 0 &&
                          pthread_attr_setstacksize(&attributes, stack) == 0 &&
                          pthread_create(&thread, &attributes, run_job, &job) == 0;
    if (threaded)
        pthread_join(thread, nullptr);
    else
        run_job(&job); // no thread to be had: the import on this stack
    _exit(write_all(fd, job.out) ? 0 : 1);
}

std::string signal_text(int signal) {
    const char* name = ::sigabbrev_np(signal);
    std::string text = "signal " + std::to_string(signal) + " (SIG" + (name ? name : "?") + ")";
    if (signal == SIGSEGV || signal == SIGBUS)
        text += ": it crashed (e.g. a stack overflow on deeply nested input, or an index past "
                "the end of the data)";
    else if (signal == SIGKILL)
        text += ": it was killed (perhaps by the system for want of memory)";
    else if (signal == SIGXCPU)
        text += ": over its time";
    return text;
}

[[noreturn]] void importer_failed(const std::filesystem::path& path, const std::string& how) {
    throw InputError(path.string() + ": the importer (assimp) failed on this file (" + how +
                     "); nothing was written");
}

// Reads the child's answer until it closes the pipe, or the deadline passes (then kills it).
std::string receive(int fd, pid_t pid, const std::filesystem::path& path,
                    const ImportLimits& limits) {
    using clock = std::chrono::steady_clock;
    const auto deadline = clock::now() + std::chrono::duration<double>(limits.seconds);
    std::string received;
    char buffer[1 << 16];
    for (;;) {
        int wait_ms = -1;
        if (limits.seconds > 0) {
            const auto left = std::chrono::duration<double>(deadline - clock::now()).count();
            wait_ms = left > 0 ? static_cast<int>(std::ceil(left * 1000)) : 0;
        }
        pollfd pfd{fd, POLLIN, 0};
        const int ready = ::poll(&pfd, 1, wait_ms);
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
            char text[160];
            std::snprintf(text, sizeof text,
                          "time: no result after %g s; --import-timeout S allows longer",
                          limits.seconds);
            importer_failed(path, text);
        }
        const auto n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        received.append(buffer, static_cast<std::size_t>(n));
    }
    return received;
}
} // namespace

Scene run_isolated(const std::filesystem::path& path, const ImportLimits& limits,
                   const std::function<Scene(SceneReport&)>& import, SceneReport& report) {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0)
        throw SystemError(std::string("cannot make a pipe for the importer: ") +
                          std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(pipe_fds[0]);
        ::close(pipe_fds[1]);
        throw SystemError(std::string("cannot start the importer's process: ") +
                          std::strerror(errno));
    }
    if (pid == 0) {
        ::close(pipe_fds[0]);
        child(pipe_fds[1], limits, import);
    }
    ::close(pipe_fds[1]);
    std::string answer;
    try {
        answer = receive(pipe_fds[0], pid, path, limits);
    } catch (...) {
        ::close(pipe_fds[0]);
        throw;
    }
    ::close(pipe_fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFSIGNALED(status)) importer_failed(path, signal_text(WTERMSIG(status)));
    if (answer.empty() || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        importer_failed(path, "its process ended with no result");
    switch (answer[0]) {
    case kScene: {
        Scene scene;
        decode_scene(std::string_view(answer).substr(1), scene, report);
        return scene;
    }
    case kInput:
        throw InputError(answer.substr(1));
    case kMemory:
        importer_failed(path, "memory: over the limit of " +
                                  human_bytes(double(limits.memory_bytes)) +
                                  "; --import-memory SIZE allows more");
    default:
        throw InternalError(answer.substr(1));
    }
}

} // namespace rad::import
