// Errors by class, as the house exit codes want them: bad input or usage (1), system
// failure such as an unwritable disk (2), anything else is internal (3).
#pragma once
#include <stdexcept>
#include <string>

namespace rad {

// Where in an input a problem is: a file, and a line for text formats (0: no line).
struct FileLoc {
    std::string file;
    int line = 0;
    // "scene.obj:42" or "scene.obj", the prefix of every message about that place.
    std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

// Bad input or usage: exit code 1.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
    InputError(const FileLoc& where, const std::string& message)
        : std::runtime_error(where.str() + ": " + message) {}
};

// The system failed us (cannot write, disk full, out of memory, a library's resource
// failure): exit code 2.
struct SystemError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A broken invariant inside radiosity or a library it calls: exit code 3.
struct InternalError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

} // namespace rad
