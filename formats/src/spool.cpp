// FormFactorSpool: rows of a form-factor matrix kept on disk until the file is written, so
// that writing a matrix larger than memory costs O(rows) memory.
#include "radfmt/kinds.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace radfmt {
namespace fs = std::filesystem;

namespace {
constexpr std::size_t kBufferEntries = std::size_t(1) << 20; // 4 MiB per array

// An unnamed file: nothing to clean up, whatever ends the run.
int open_unnamed_file(const fs::path& folder) {
    const auto where = folder.empty() ? fs::path(".") : folder;
    int fd = ::open(where.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd >= 0) return fd;
    // A file system without O_TMPFILE: a named file, unlinked at once.
    std::string name = (where / ".rad-spool.XXXXXX").string();
    fd = ::mkstemp(name.data());
    if (fd < 0) return -1;
    ::unlink(name.c_str());
    return fd;
}

void write_all(int fd, const void* data, std::size_t size, const std::string& folder) {
    const auto* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const auto done = ::write(fd, bytes, size);
        if (done < 0 && errno == EINTR) continue;
        if (done <= 0)
            throw WriteError(folder + ": cannot keep the form factors being computed there (" +
                             std::strerror(done < 0 ? errno : ENOSPC) +
                             "): the rows wait on disk until the file is written, and need "
                             "about as much room as it will take");
        bytes += done;
        size -= static_cast<std::size_t>(done);
    }
}
} // namespace

FormFactorSpool::FormFactorSpool(std::uint64_t patch_count, const fs::path& spill_folder)
    : patch_count_(patch_count), folder_(spill_folder.empty() ? "." : spill_folder.string()) {
    back_fraction_.reserve(patch_count);
    row_start_.reserve(patch_count + 1);
    column_buffer_.reserve(kBufferEntries);
    value_buffer_.reserve(kBufferEntries);
    columns_fd_ = open_unnamed_file(spill_folder);
    values_fd_ = columns_fd_ < 0 ? -1 : open_unnamed_file(spill_folder);
    if (columns_fd_ < 0 || values_fd_ < 0) {
        const int error = errno;
        if (columns_fd_ >= 0) ::close(columns_fd_);
        throw WriteError(folder_ + ": cannot create a temporary file for the rows (" +
                         std::strerror(error) + ")");
    }
}

FormFactorSpool::~FormFactorSpool() {
    if (columns_fd_ >= 0) ::close(columns_fd_);
    if (values_fd_ >= 0) ::close(values_fd_);
}

void FormFactorSpool::add_row(std::span<const std::uint32_t> columns, std::span<const float> values,
                              float back_fraction) {
    if (columns.size() != values.size() || rows() >= patch_count_)
        throw std::logic_error("FormFactorSpool: a row with unequal arrays, or too many rows");
    for (std::size_t k = 0; k < columns.size(); ++k) {
        column_buffer_.push_back(columns[k]);
        value_buffer_.push_back(values[k]);
        if (column_buffer_.size() == kBufferEntries) flush();
    }
    row_start_.push_back(row_start_.back() + columns.size());
    back_fraction_.push_back(back_fraction);
}

void FormFactorSpool::add_row(std::span<const std::pair<std::uint32_t, float>> entries,
                              float back_fraction) {
    if (rows() >= patch_count_) throw std::logic_error("FormFactorSpool: too many rows");
    for (const auto& [column, value] : entries) {
        column_buffer_.push_back(column);
        value_buffer_.push_back(value);
        if (column_buffer_.size() == kBufferEntries) flush();
    }
    row_start_.push_back(row_start_.back() + entries.size());
    back_fraction_.push_back(back_fraction);
}

fs::path FormFactorSpool::folder_for(const fs::path& output) {
    std::error_code ec;
    const auto status = fs::status(output, ec);
    if (fs::exists(status) && !fs::is_regular_file(status)) return fs::temp_directory_path();
    return output.has_parent_path() ? output.parent_path() : fs::path(".");
}

void FormFactorSpool::flush() {
    write_all(columns_fd_, column_buffer_.data(), column_buffer_.size() * sizeof(std::uint32_t),
              folder_);
    write_all(values_fd_, value_buffer_.data(), value_buffer_.size() * sizeof(float), folder_);
    column_buffer_.clear();
    value_buffer_.clear();
}

void FormFactorSpool::fill_body(BodyWriter& body) {
    if (rows() != patch_count_)
        throw std::logic_error("FormFactorSpool: written before every row was added");
    flush();
    body.u64(patch_count_);
    body.u64(nonzeros());
    body.array(row_start_);
    body.file_array(columns_fd_, nonzeros() * sizeof(std::uint32_t));
    body.file_array(values_fd_, nonzeros() * sizeof(float));
    body.array(back_fraction_);
}

} // namespace radfmt
