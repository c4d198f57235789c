#include "radiosity/text_input.hpp"

#include "radiosity/numbers.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rad {

std::string quoted_prefix(std::string_view text) {
    constexpr std::size_t kShown = 60;
    std::string out = "'";
    for (const char c : text.substr(0, kShown))
        out += (static_cast<unsigned char>(c) < 32 || c == 127) ? '?' : c;
    return out + (text.size() > kShown ? "...'" : "'");
}

LineReader::LineReader(const std::string& path, const std::string& stdin_name,
                       std::size_t max_line_bytes)
    : buffer_(std::size_t(1) << 16), max_line_(max_line_bytes) {
    if (path.empty() || path == "-") {
        fd_ = 0;
        name_ = stdin_name;
    } else {
        name_ = path;
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0)
            throw InputError(FileLoc{path}, std::string("cannot open it: ") + std::strerror(errno));
        owned_ = true;
    }
    struct stat st {};
    if (::fstat(fd_, &st) == 0 && S_ISDIR(st.st_mode)) {
        if (owned_) ::close(fd_);
        fd_ = -1;
        throw InputError(FileLoc{name_}, "is a folder, not a text file");
    }
}

LineReader::~LineReader() {
    if (owned_ && fd_ >= 0) ::close(fd_);
}

bool LineReader::fill() {
    if (eof_) return false;
    if (begin_ > 0) { // keep the unread part at the front
        std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
        end_ -= begin_;
        begin_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
    for (;;) {
        const auto got = ::read(fd_, buffer_.data() + end_, buffer_.size() - end_);
        if (got > 0) {
            end_ += std::size_t(got);
            return true;
        }
        if (got == 0) {
            eof_ = true;
            return false;
        }
        if (errno == EINTR) continue;
        if (errno == EISDIR) throw InputError(FileLoc{name_}, "is a folder, not a text file");
        throw SystemError(FileLoc{name_, line_ + 1}.str() +
                          ": cannot read: " + std::strerror(errno));
    }
}

// A line ends at LF, CR LF or a lone CR (as tinyobjloader and old Mac files have it).
bool LineReader::next(std::string& line) {
    std::size_t scanned = begin_;
    for (;;) {
        std::size_t stop = scanned;
        while (stop < end_ && buffer_[stop] != '\n' && buffer_[stop] != '\r') ++stop;
        // A CR last in the buffer may be the first half of CR LF: read on before deciding.
        const bool ends = stop < end_ && (buffer_[stop] == '\n' || stop + 1 < end_ || eof_);
        if (stop - begin_ > max_line_)
            throw InputError(FileLoc{name_, line_ + 1},
                             "a line longer than " + human_bytes(double(max_line_)) +
                                 " (the longest a line may be), starting " +
                                 quoted_prefix({buffer_.data() + begin_, 60}) +
                                 ": not a text file of this kind?");
        if (std::memchr(buffer_.data() + scanned, '\0', stop - scanned))
            throw InputError(FileLoc{name_, line_ + 1},
                             "holds a NUL byte: not a text file (a binary file or a device?)");
        if (ends || (eof_ && stop == end_ && stop > begin_)) {
            line.assign(buffer_.data() + begin_, stop - begin_);
            begin_ = stop;
            if (ends) {
                const bool crlf =
                    buffer_[stop] == '\r' && stop + 1 < end_ && buffer_[stop + 1] == '\n';
                begin_ = stop + (crlf ? 2 : 1);
            }
            ++line_;
            return true;
        }
        const std::size_t offset = stop - begin_; // fill() may move the unread part
        const bool more = fill();
        scanned = begin_ + offset;
        if (!more && end_ == begin_) return false;
        // Else: more to scan, or a last line without its end.
    }
}

} // namespace rad
