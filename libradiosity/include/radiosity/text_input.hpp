// Text inputs read line by line with every failure told apart: the end of the file, a read
// that failed (exit 2), a folder or a line longer than kMaxLineBytes (exit 1), each naming the
// file and the line. Messages quote at most a short prefix of a line (quoted_prefix), so a
// huge bad line never floods stderr.
#pragma once
#include "radiosity/error.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

// The longest line a text input of the chain may have (points, views, layouts): 1 MiB.
inline constexpr std::size_t kMaxLineBytes = std::size_t(1) << 20;

// 'text' for a message: at most 60 bytes of it, control bytes shown as '?', "..." when cut.
std::string quoted_prefix(std::string_view text);

class LineReader {
  public:
    // Opens `path` ("-" or empty: standard input, named `stdin_name`). A folder, or a file
    // that cannot be opened, is refused here (InputError naming it).
    explicit LineReader(const std::string& path, const std::string& stdin_name = "<stdin>",
                        std::size_t max_line_bytes = kMaxLineBytes);
    ~LineReader();
    LineReader(const LineReader&) = delete;
    LineReader& operator=(const LineReader&) = delete;

    // The next line, without its LF or CR LF; false at the end of the input. Throws
    // InputError "NAME:LINE: ..." for a line over the limit or holding a NUL byte (not
    // text), SystemError for a failed read.
    bool next(std::string& line);
    int line_number() const { return line_; }
    const std::string& name() const { return name_; }

  private:
    bool fill();
    int fd_ = -1;
    bool owned_ = false, eof_ = false;
    std::string name_;
    std::vector<char> buffer_;
    std::size_t begin_ = 0, end_ = 0;
    int line_ = 0;
    std::size_t max_line_;
};

// The longest line of an OBJ or MTL file: 64 MiB (a face of millions of corners fits).
inline constexpr std::size_t kMaxSceneLineBytes = std::size_t(64) << 20;

} // namespace rad
