// FormFactorSpool: rows of a form-factor matrix kept in chunks until the file is written,
// spilled to disk past a memory budget.
#include "radfmt/kinds.hpp"

#include "compact_rows.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace radfmt {
namespace fs = std::filesystem;

namespace {
// Entries per chunk (4 MiB per array). A multiple of two, so chunk boundaries fall on the
// 8-byte alignment of the body and the chunks lay out as one contiguous array.
constexpr std::size_t kChunkEntries = std::size_t(1) << 20;

// An unnamed file: nothing to clean up, whatever ends the run.
int open_unnamed_file(const fs::path& folder) {
    int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd >= 0) return fd;
    // A file system without O_TMPFILE: a named file, unlinked at once.
    std::string name = (folder / ".rad-spool.XXXXXX").string();
    fd = ::mkstemp(name.data());
    if (fd < 0) return -1;
    ::unlink(name.c_str());
    return fd;
}

void write_all(int fd, const void* data, std::size_t size, const fs::path& folder) {
    const auto* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const auto done = ::write(fd, bytes, size);
        if (done < 0 && errno == EINTR) continue;
        if (done <= 0)
            throw WriteError(folder.string() +
                             ": cannot keep the form factors being computed there (" +
                             std::strerror(done < 0 ? errno : ENOSPC) +
                             "): rows beyond the memory limit wait on disk until the file is "
                             "written, and need about as much room as it will take");
        bytes += done;
        size -= static_cast<std::size_t>(done);
    }
}
} // namespace

FormFactorSpool::FormFactorSpool(std::uint64_t patch_count, const fs::path& spill_folder,
                                 std::uint64_t memory_budget, std::optional<std::uint64_t> compact)
    : patch_count_(patch_count), folder_(spill_folder.empty() ? fs::path(".") : spill_folder),
      memory_budget_(memory_budget), compact_(compact) {
    back_fraction_.reserve(patch_count);
    row_start_.reserve(patch_count + 1);
    if (compact_) row_offset_.reserve(patch_count + 1);
}

FormFactorSpool::~FormFactorSpool() {
    if (columns_fd_ >= 0) ::close(columns_fd_);
    if (values_fd_ >= 0) ::close(values_fd_);
    if (code_fd_ >= 0) ::close(code_fd_);
}

void FormFactorSpool::add_entry(std::uint32_t column, float value) {
    if (column_chunks_.empty() || column_chunks_.back().size() == kChunkEntries) chunk_full();
    column_chunks_.back().push_back(column);
    value_chunks_.back().push_back(value);
}

// A new chunk in memory while the budget allows, else the entries so far go to disk and
// the chunk is reused.
void FormFactorSpool::chunk_full() {
    const std::uint64_t chunk_bytes = kChunkEntries * (sizeof(std::uint32_t) + sizeof(float));
    if (!spilled() && (column_chunks_.size() + 1) * chunk_bytes > memory_budget_) spill();
    if (spilled() && !column_chunks_.empty()) {
        write_all(columns_fd_, column_chunks_.back().data(),
                  column_chunks_.back().size() * sizeof(std::uint32_t), folder_);
        write_all(values_fd_, value_chunks_.back().data(),
                  value_chunks_.back().size() * sizeof(float), folder_);
        column_chunks_.back().clear();
        value_chunks_.back().clear();
        return;
    }
    column_chunks_.emplace_back().reserve(kChunkEntries);
    value_chunks_.emplace_back().reserve(kChunkEntries);
}

void FormFactorSpool::spill() {
    columns_fd_ = open_unnamed_file(folder_);
    values_fd_ = columns_fd_ < 0 ? -1 : open_unnamed_file(folder_);
    if (columns_fd_ < 0 || values_fd_ < 0) {
        const int error = errno;
        throw WriteError(folder_.string() + ": cannot create a temporary file for the rows (" +
                         std::strerror(error) + ")");
    }
    // Every chunk but the last goes to disk now; the last is written when full.
    while (column_chunks_.size() > 1) {
        write_all(columns_fd_, column_chunks_.front().data(),
                  column_chunks_.front().size() * sizeof(std::uint32_t), folder_);
        write_all(values_fd_, value_chunks_.front().data(),
                  value_chunks_.front().size() * sizeof(float), folder_);
        column_chunks_.erase(column_chunks_.begin());
        value_chunks_.erase(value_chunks_.begin());
    }
}

namespace {
constexpr std::size_t kCodeBlock = std::size_t(4)
                                   << 20; // a multiple of 8: blocks lay out as one array
} // namespace

// The first `bytes` of the pending code as a block: in memory while the budget allows, then
// (with every block before it) to a spill file.
void FormFactorSpool::store_code(std::size_t bytes) {
    if (code_fd_ < 0 && (code_blocks_.size() + 1) * kCodeBlock > memory_budget_) {
        code_fd_ = open_unnamed_file(folder_);
        if (code_fd_ < 0)
            throw WriteError(folder_.string() + ": cannot create a temporary file for the rows (" +
                             std::strerror(errno) + ")");
        for (const auto& block : code_blocks_)
            write_all(code_fd_, block.data(), block.size(), folder_);
        code_blocks_.clear();
    }
    if (code_fd_ >= 0)
        write_all(code_fd_, code_.data(), bytes, folder_);
    else
        code_blocks_.emplace_back(code_.begin(), code_.begin() + long(bytes));
    code_.erase(code_.begin(), code_.begin() + long(bytes));
    code_stored_ += bytes;
}

// A row's code after the others, full blocks stored, and where the next row's code starts.
void FormFactorSpool::encode_code_row(std::span<const std::uint32_t> columns,
                                      std::span<const float> values) {
    compact::encode_row(columns, values, *compact_, code_);
    while (code_.size() >= kCodeBlock) store_code(kCodeBlock);
    row_offset_.push_back(code_stored_ + code_.size());
}

void FormFactorSpool::add_compact_row(std::span<const std::uint32_t> columns,
                                      std::span<const float> values, float back_fraction) {
    encode_code_row(columns, values);
    row_start_.push_back(row_start_.back() + columns.size());
    back_fraction_.push_back(back_fraction);
}

void FormFactorSpool::add_row(std::span<const std::uint32_t> columns, std::span<const float> values,
                              float back_fraction) {
    if (columns.size() != values.size() || rows() >= patch_count_)
        throw std::logic_error("FormFactorSpool: a row with unequal arrays, or too many rows");
    if (compact_) return add_compact_row(columns, values, back_fraction);
    for (std::size_t k = 0; k < columns.size(); ++k) add_entry(columns[k], values[k]);
    row_start_.push_back(row_start_.back() + columns.size());
    back_fraction_.push_back(back_fraction);
}

void FormFactorSpool::add_row(std::span<const std::pair<std::uint32_t, float>> entries,
                              float back_fraction) {
    if (rows() >= patch_count_) throw std::logic_error("FormFactorSpool: too many rows");
    if (compact_) { // split into the spool's scratch arrays (no allocation once they are grown)
        scratch_columns_.resize(entries.size());
        scratch_values_.resize(entries.size());
        for (std::size_t k = 0; k < entries.size(); ++k)
            scratch_columns_[k] = entries[k].first, scratch_values_[k] = entries[k].second;
        return add_compact_row(scratch_columns_, scratch_values_, back_fraction);
    }
    for (const auto& [column, value] : entries) add_entry(column, value);
    row_start_.push_back(row_start_.back() + entries.size());
    back_fraction_.push_back(back_fraction);
}

void FormFactorSpool::add_row_error(float error) {
    if (row_error_.size() + 1 != rows())
        throw std::logic_error("FormFactorSpool: a row error for no row, or a row without one");
    row_error_.push_back(error);
}

void FormFactorSpool::fill_row_errors(BodyWriter& body) const {
    if (row_error_.empty()) return;
    if (row_error_.size() != patch_count_)
        throw std::logic_error("FormFactorSpool: written with some rows' errors missing");
    body.array(row_error_);
}

fs::path FormFactorSpool::folder_for(const fs::path& output) {
    if (is_special_target(output)) return fs::temp_directory_path();
    return output.has_parent_path() ? output.parent_path() : fs::path(".");
}

void FormFactorSpool::fill_body(BodyWriter& body) {
    if (rows() != patch_count_ || compact_)
        throw std::logic_error("FormFactorSpool: written before every row was added, or a "
                               "compact spool written as plain arrays");
    body.u64(patch_count_);
    body.u64(nonzeros());
    body.array(row_start_);
    if (spilled()) {
        chunk_full(); // the last chunk to disk
        body.file_array(columns_fd_, nonzeros() * sizeof(std::uint32_t));
        body.file_array(values_fd_, nonzeros() * sizeof(float));
    } else {
        // Chunks of an even number of 4-byte entries: no padding between them.
        for (const auto& chunk : column_chunks_) body.array(chunk);
        for (const auto& chunk : value_chunks_) body.array(chunk);
    }
    body.array(back_fraction_);
    fill_row_errors(body);
}

namespace {

// The spool's entries in order, from its chunks in memory (each released once read) or from
// its two spill files.
class EntrySource {
  public:
    EntrySource(std::vector<std::vector<std::uint32_t>>& columns,
                std::vector<std::vector<float>>& values, int columns_fd, int values_fd)
        : columns_(columns), values_(values), columns_fd_(columns_fd), values_fd_(values_fd) {}

    void next(std::size_t n, std::vector<std::uint32_t>& columns, std::vector<float>& values) {
        columns.resize(n);
        values.resize(n);
        for (std::size_t k = 0; k < n;) {
            if (at_ == size()) refill();
            const std::size_t take = std::min(n - k, size() - at_);
            std::memcpy(columns.data() + k, column_block().data() + at_, take * 4);
            std::memcpy(values.data() + k, value_block().data() + at_, take * 4);
            at_ += take;
            k += take;
        }
    }

  private:
    bool spilled() const { return columns_fd_ >= 0; }
    std::size_t size() const { return spilled() ? block_columns_.size() : current_size_; }
    const std::vector<std::uint32_t>& column_block() const {
        return spilled() ? block_columns_ : columns_[chunk_ - 1];
    }
    const std::vector<float>& value_block() const {
        return spilled() ? block_values_ : values_[chunk_ - 1];
    }
    void refill() {
        at_ = 0;
        if (!spilled()) {
            if (chunk_ > 0) { // the chunk read is no longer needed
                std::vector<std::uint32_t>().swap(columns_[chunk_ - 1]);
                std::vector<float>().swap(values_[chunk_ - 1]);
            }
            if (chunk_ >= columns_.size())
                throw std::logic_error("FormFactorSpool: entries ran out");
            current_size_ = columns_[chunk_++].size();
            return;
        }
        block_columns_.resize(kChunkEntries);
        block_values_.resize(kChunkEntries);
        const auto got_columns = ::pread(columns_fd_, block_columns_.data(), kChunkEntries * 4,
                                         static_cast<off_t>(offset_));
        const auto got_values = ::pread(values_fd_, block_values_.data(), kChunkEntries * 4,
                                        static_cast<off_t>(offset_));
        if (got_columns <= 0 || got_columns != got_values || got_columns % 4 != 0)
            throw WriteError(std::string("cannot read back the spilled rows: ") +
                             (got_columns < 0 ? std::strerror(errno) : "short read"));
        offset_ += std::uint64_t(got_columns);
        block_columns_.resize(std::size_t(got_columns) / 4);
        block_values_.resize(std::size_t(got_columns) / 4);
    }

    std::vector<std::vector<std::uint32_t>>& columns_;
    std::vector<std::vector<float>>& values_;
    int columns_fd_, values_fd_;
    std::size_t chunk_ = 0, current_size_ = 0, at_ = 0;
    std::uint64_t offset_ = 0;
    std::vector<std::uint32_t> block_columns_;
    std::vector<float> block_values_;
};

} // namespace

// A plain spool written as formfactors: its entries encoded now, each chunk released once read.
void FormFactorSpool::reencode_rows(std::uint64_t denominator) {
    if (columns_fd_ >= 0) chunk_full(); // the last chunk to disk
    EntrySource entries(column_chunks_, value_chunks_, columns_fd_, values_fd_);
    std::vector<std::uint32_t> columns;
    std::vector<float> values;
    compact_ = denominator;
    for (std::uint64_t i = 0; i < patch_count_; ++i) {
        entries.next(static_cast<std::size_t>(row_start_[i + 1] - row_start_[i]), columns, values);
        encode_code_row(columns, values);
    }
}

void FormFactorSpool::fill_compact_body(BodyWriter& body, std::uint64_t denominator) {
    if (rows() != patch_count_)
        throw std::logic_error("FormFactorSpool: written before every row was added");
    if (!compact_) reencode_rows(denominator);
    if (*compact_ != denominator)
        throw std::logic_error("FormFactorSpool: encoded for another hit denominator");
    if (!code_.empty()) store_code(code_.size());
    body.u64(patch_count_);
    body.u64(nonzeros());
    body.u64(denominator);
    body.array(row_start_);
    body.array(row_offset_);
    if (code_fd_ >= 0) {
        body.file_array(code_fd_, code_stored_);
    } else {
        for (const auto& block : code_blocks_) body.array(block);
    }
    body.array(back_fraction_);
    fill_row_errors(body);
}

} // namespace radfmt
