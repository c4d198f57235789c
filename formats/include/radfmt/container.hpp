// The container shared by every file of the chain: a text header with provenance,
// then an aligned little-endian binary body. See formats/README.md for the byte layout.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace radfmt {

inline constexpr std::string_view kMagic = "#?RADIOSITY-FILE";
inline constexpr std::uint32_t kContainerVersion = 1;
inline constexpr std::size_t kBodyAlignment = 64;
inline constexpr std::size_t kMaxHeaderBytes = 1 << 20;

// Every problem with a file's contents is a FormatError whose message starts with the
// file's path: bad input (exit code 1).
struct FormatError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
// The system refused a write (cannot create, disk full, rename failed): exit code 2.
struct WriteError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The file kinds; what each is (name, description, version, CSV, summary) is the table in
// kinds.hpp, which the container and rad-info read.
enum class Kind { Mesh, FormFactors, Radiosity, FormFactorPart, Links, Luminaires, Sky, Annual };
std::string_view kind_name(Kind kind);
std::string_view kind_description(Kind kind);
std::uint32_t kind_version(Kind kind);
bool parse_kind(std::string_view name, Kind& kind);

struct InputRecord {
    std::string path;
    std::string hash; // "xxh64:" + 16 hex digits
};

struct Header {
    Kind kind = Kind::Mesh;
    std::uint32_t version = 0;
    std::string tool;                    // producing tool and its version
    std::string command;                 // producing command line
    std::vector<std::string> provenance; // commands of the ancestors, oldest first
    std::vector<InputRecord> inputs;
    std::vector<std::pair<std::string, std::string>> fields; // kind-specific facts
    std::uint64_t body_size = 0;
    std::string body_hash;
    // Set by BodyReader::expect_end (not stored): xxh64 of the whole file as read, for the input
    // records of files derived from it, so no tool reads a large input twice to hash it.
    std::string file_hash;

    void set(const std::string& key, const std::string& value);
    // Returns the field or throws FormatError naming `path` when it is missing.
    const std::string& get(const std::string& key, const std::string& path) const;
    const std::string* find(const std::string& key) const;
    // Ancestors plus this file's own command: what a file derived from this one inherits.
    std::vector<std::string> chain() const;
};

std::string hash_hex(std::uint64_t hash);
std::uint64_t hash_bytes(const void* data, std::size_t size);
// xxh64 of a whole file's bytes, as "xxh64:<hex>"; throws FormatError if unreadable.
std::string hash_file(const std::filesystem::path& path);

// Lays out a body, keeping every value and array aligned to 8 bytes. Arrays are referenced,
// not copied (a form-factor body can be gigabytes): they must outlive the writer's use. So
// must the files that file_array pieces come from.
class BodyWriter {
  public:
    void u64(std::uint64_t value);
    void string(std::string_view text);
    template <class T> void array(std::span<const T> values) {
        static_assert(std::is_trivially_copyable_v<T>);
        align();
        add(reinterpret_cast<const std::byte*>(values.data()), values.size_bytes(), false);
        align();
    }
    template <class T> void array(const std::vector<T>& values) {
        array(std::span<const T>(values.data(), values.size()));
    }
    // An array already written to an open file (bytes [0, size) of `fd`): a body larger
    // than memory is read from there block by block when hashed and when written.
    void file_array(int fd, std::uint64_t size);
    std::uint64_t size() const { return size_; }
    // Hands the body's bytes to `sink` piece by piece, in order (file pieces in blocks).
    void for_each_piece(const std::function<void(const std::byte*, std::size_t)>& sink) const;
    std::uint64_t hash() const; // xxh64 of the body

  private:
    void align();
    void add(const std::byte* data, std::size_t size, bool copy);
    struct Piece {
        const std::byte* external; // nullptr: the bytes are owned_[offset, offset + size)
        std::size_t offset, size;
        int fd = -1; // >= 0: the bytes are [0, size) of this file
    };
    std::vector<Piece> pieces_;
    std::vector<std::byte> owned_; // scalars, strings and padding
    std::uint64_t size_ = 0;
};

// Reads a file of the chain: the header is checked when the reader is made; the body is
// read in order, straight into the arrays that keep it, and hashed on the way, so a large
// body is never held twice. expect_end() checks the body's checksum. Every failure names
// the file; a wrong value in a body whose checksum is wrong too is reported as the
// checksum mismatch (the rest of the body is read to tell).
class BodyReader {
  public:
    // Refuses a file of another kind than `expected`, when given.
    explicit BodyReader(const std::filesystem::path& path, const Kind* expected = nullptr);
    ~BodyReader();
    BodyReader(const BodyReader&) = delete;
    BodyReader& operator=(const BodyReader&) = delete;

    const Header& header() const { return header_; }
    // The header, with file_hash set once expect_end() has run.
    Header take_header() { return std::move(header_); }

    std::uint64_t u64();
    std::string string();
    // Reads a count that will size an array of `element_size` bytes: refuses counts that
    // cannot fit in the rest of the body, so corrupt counts never drive huge allocations.
    std::uint64_t count(std::size_t element_size, const char* what);
    template <class T> std::vector<T> array(std::uint64_t count, const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        align();
        need(count * sizeof(T), what);
        std::vector<T> out(count);
        read(out.data(), count * sizeof(T));
        align();
        return out;
    }
    // An array read in pieces (too large to hold twice): begin_pieces checks that `bytes`
    // remain, read_piece reads the next part, end_pieces passes the padding after it.
    void begin_pieces(std::uint64_t bytes, const char* what) {
        align();
        need(bytes, what);
    }
    void read_piece(void* into, std::uint64_t bytes) { read(into, bytes); }
    void end_pieces() { align(); }
    // Requires the end of the body and checks its checksum: call it before trusting values.
    void expect_end();
    [[noreturn]] void fail(const std::string& message);

  private:
    void align();
    void need(std::uint64_t bytes, const char* what);
    void read(void* into, std::uint64_t bytes);
    void check_checksum();
    std::string path_;
    Header header_;
    std::FILE* file_ = nullptr;
    std::uint64_t pos_ = 0;      // within the body
    void* body_state_ = nullptr; // XXH64_state_t of the body so far
    void* file_state_ = nullptr; // XXH64_state_t of the whole file so far
    bool checked_ = false;
};

// Serialises header and body to `path` atomically: a temporary file in the same folder is
// written, flushed and renamed into place, so no reader ever sees a half-written file.
void write_file(const std::filesystem::path& path, Header header, const BodyWriter& body);

// Reads only the header (still validating its checksum); fast for large files.
Header read_header(const std::filesystem::path& path, const Kind* expected = nullptr);

// An existing output that is neither a regular file nor a folder (a device, a FIFO): it is
// written in place, not through a temporary file beside it.
bool is_special_target(const std::filesystem::path& path);

// Writes a file atomically through a callback that fills a temporary path.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& fill);

// While an OutputBatch is alive, write_atomically fills each output's temporary file but
// renames none into place; commit() renames them all. Destroyed without commit (a later
// output failed, an exception), it removes them: a run leaves all its outputs or none.
// Outputs that are devices (/dev/null) are written at once and are not part of it.
namespace detail {
struct PendingOutput {
    std::filesystem::path temp, target;
    std::size_t slot; // in the signal handler's table
};
} // namespace detail

class OutputBatch {
  public:
    OutputBatch();
    ~OutputBatch();
    OutputBatch(const OutputBatch&) = delete;
    OutputBatch& operator=(const OutputBatch&) = delete;
    void commit();

  private:
    std::vector<detail::PendingOutput> pending_;
};

// The temporary path currently being written, removed by signal handlers (see
// install_cleanup_handlers) so Ctrl-C never leaves a partial file behind.
void install_cleanup_handlers();

} // namespace radfmt
