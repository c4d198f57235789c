#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"

#include <xxhash.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace radfmt {
namespace fs = std::filesystem;

void Header::set(const std::string& key, const std::string& value) {
    for (auto& [k, v] : fields) {
        if (k == key) {
            v = value;
            return;
        }
    }
    fields.emplace_back(key, value);
}

const std::string* Header::find(const std::string& key) const {
    for (const auto& [k, v] : fields)
        if (k == key) return &v;
    return nullptr;
}

const std::string& Header::get(const std::string& key, const std::string& path) const {
    if (const auto* v = find(key)) return *v;
    throw FormatError(path + ": header has no '" + key + "' field");
}

std::vector<std::string> Header::chain() const {
    auto out = provenance;
    out.push_back(command);
    return out;
}

using HashState = std::unique_ptr<XXH64_state_t, decltype(&XXH64_freeState)>;

std::string hash_hex(std::uint64_t hash) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

std::uint64_t hash_bytes(const void* data, std::size_t size) {
    return XXH64(data, size, 0);
}

std::string hash_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FormatError(path.string() + ": cannot open for reading");
    const HashState state(XXH64_createState(), XXH64_freeState);
    XXH64_reset(state.get(), 0);
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        XXH64_update(state.get(), buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
    const auto hash = XXH64_digest(state.get());
    return "xxh64:" + hash_hex(hash);
}

// ---- body encoding ----

void BodyWriter::add(const std::byte* data, std::size_t size, bool copy) {
    if (size == 0) return;
    if (copy) {
        pieces_.push_back({nullptr, owned_.size(), size});
        owned_.insert(owned_.end(), data, data + size);
    } else {
        pieces_.push_back({data, 0, size});
    }
    size_ += size;
}

void BodyWriter::u64(std::uint64_t value) {
    align();
    std::byte raw[8];
    for (int i = 0; i < 8; ++i) raw[i] = std::byte((value >> (8 * i)) & 0xff);
    add(raw, 8, true);
}

void BodyWriter::string(std::string_view text) {
    u64(text.size());
    add(reinterpret_cast<const std::byte*>(text.data()), text.size(), true);
    align();
}

void BodyWriter::align() {
    static constexpr std::byte zeros[8] = {};
    if (size_ % 8) add(zeros, 8 - size_ % 8, true);
}

void BodyWriter::file_array(int fd, std::uint64_t size) {
    align();
    if (size) {
        pieces_.push_back({nullptr, 0, static_cast<std::size_t>(size), fd});
        size_ += size;
    }
    align();
}

void BodyWriter::for_each_piece(
    const std::function<void(const std::byte*, std::size_t)>& sink) const {
    std::vector<std::byte> block;
    for (const auto& piece : pieces_) {
        if (piece.fd < 0) {
            sink(piece.external ? piece.external : owned_.data() + piece.offset, piece.size);
            continue;
        }
        block.resize(std::min<std::size_t>(piece.size, std::size_t(8) << 20));
        for (std::size_t at = 0; at < piece.size;) {
            const auto want = std::min(block.size(), piece.size - at);
            const auto got = ::pread(piece.fd, block.data(), want, static_cast<off_t>(at));
            if (got <= 0)
                throw WriteError(std::string("cannot read back a spooled array: ") +
                                 (got < 0 ? std::strerror(errno) : "it is shorter than written"));
            sink(block.data(), static_cast<std::size_t>(got));
            at += static_cast<std::size_t>(got);
        }
    }
}

std::uint64_t BodyWriter::hash() const {
    const HashState state(XXH64_createState(), XXH64_freeState);
    XXH64_reset(state.get(), 0);
    for_each_piece(
        [&](const std::byte* data, std::size_t size) { XXH64_update(state.get(), data, size); });
    return XXH64_digest(state.get());
}

// ---- header text ----

static std::string escape(std::string_view value) {
    std::string out;
    for (char c : value) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '\n')
            out += "\\n";
        else if (c == '\r')
            out += "\\r";
        else
            out += c;
    }
    return out;
}

static std::string unescape(std::string_view value) {
    std::string out;
    for (std::size_t i = 0; i < value.size(); ++i) {
        if (value[i] == '\\' && i + 1 < value.size()) {
            char next = value[++i];
            out += next == 'n' ? '\n' : next == 'r' ? '\r' : next;
        } else {
            out += value[i];
        }
    }
    return out;
}

// Header lines before the checksum line; the checksum covers exactly these bytes.
static std::string header_text(const Header& h) {
    std::ostringstream out;
    out << kMagic << ' ' << kContainerVersion << '\n';
    out << "kind=" << kind_name(h.kind) << '\n';
    out << "version=" << h.version << '\n';
    out << "tool=" << escape(h.tool) << '\n';
    out << "command=" << escape(h.command) << '\n';
    for (const auto& p : h.provenance) out << "provenance=" << escape(p) << '\n';
    for (const auto& in : h.inputs) out << "input=" << in.hash << ' ' << escape(in.path) << '\n';
    for (const auto& [k, v] : h.fields) out << "field." << k << '=' << escape(v) << '\n';
    out << "body_size=" << h.body_size << '\n';
    out << "body_hash=" << h.body_hash << '\n';
    return out.str();
}

static std::string serialise_header(const Header& h) {
    // A field's name is written as it is: one that would break its line, or its key=value
    // split, would make a file no reader accepts.
    for (const auto& [k, v] : h.fields)
        if (k.empty() || k.find_first_of("=\n\r") != std::string::npos)
            throw FormatError("not written: a header field's name '" + escape(k.substr(0, 60)) +
                              "' is empty or holds '=' or a line break");
    auto text = header_text(h);
    text += "header_hash=xxh64:" + hash_hex(hash_bytes(text.data(), text.size())) + "\n\n";
    text.resize((text.size() + kBodyAlignment - 1) / kBodyAlignment * kBodyAlignment, '\0');
    return text;
}

// ---- atomic writes ----

namespace {
// Signal handlers may only touch plain memory: the temporary paths being written (one, or
// every pending output of an OutputBatch) are kept as C strings in fixed slots.
constexpr std::size_t kTempSlots = 4096;
std::atomic<char*> g_temp_paths[kTempSlots];

extern "C" void remove_temp_and_exit(int signal_number) {
    for (auto& slot : g_temp_paths)
        if (char* path = slot.load()) ::unlink(path);
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

// Registers a temporary path for removal on a signal; returns its slot (or kTempSlots when
// all are taken: that file is then only removed by the next run, as a stale one).
std::size_t register_temp(const std::string& path) {
    for (std::size_t i = 0; i < kTempSlots; ++i) {
        if (g_temp_paths[i].load()) continue;
        char* copy = ::strdup(path.c_str());
        char* expected = nullptr;
        if (copy && g_temp_paths[i].compare_exchange_strong(expected, copy)) return i;
        std::free(copy);
    }
    return kTempSlots;
}

void unregister_temp(std::size_t slot) {
    if (slot < kTempSlots) std::free(g_temp_paths[slot].exchange(nullptr));
}

// Outputs filled but not yet renamed into place while an OutputBatch is alive.
using detail::PendingOutput;
std::vector<PendingOutput>* g_pending = nullptr;

void discard(const PendingOutput& p) {
    std::error_code ignored;
    fs::remove(p.temp, ignored);
    unregister_temp(p.slot);
}

void rename_into_place(const PendingOutput& p) {
    std::error_code ec;
    fs::rename(p.temp, p.target, ec);
    if (ec) {
        discard(p);
        throw WriteError(p.target.string() + ": cannot rename into place: " + ec.message());
    }
    unregister_temp(p.slot);
}

// ".NAME.tmp.PID.TAG" (or an older run's ".NAME.tmp.PID") files beside `target` left by a
// run that was killed (SIGKILL cannot be caught): removed when nobody holds the file's lock
// and its PID is not another live process here. A held lock always keeps the file, whatever
// its PID says: a PID says nothing of a writer in another PID namespace (two containers on
// one volume are both PID 1) or on another machine.
void remove_stale_temps(const fs::path& dir, const std::string& prefix) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const auto name = it->path().filename().string();
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
        const auto rest = name.substr(prefix.size());
        const auto dot = rest.find('.');
        const auto digits = rest.substr(0, dot);
        const auto tag = dot == std::string::npos ? std::string() : rest.substr(dot + 1);
        if (digits.empty() || digits.size() > 9 ||
            digits.find_first_not_of("0123456789") != std::string::npos ||
            tag.find_first_not_of("0123456789abcdef") != std::string::npos)
            continue;
        const int fd = ::open(it->path().c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
        if (fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            ::close(fd); // being written
            continue;
        }
        const auto pid = static_cast<pid_t>(std::stol(digits));
        if (pid != ::getpid() && (::kill(pid, 0) == 0 || errno != ESRCH)) {
            if (fd >= 0) ::close(fd); // perhaps a writer of an older kind, still alive
            continue;
        }
        ::unlink(it->path().c_str()); // a regular file, or a link planted there (not followed)
        if (fd >= 0) ::close(fd);
    }
}

std::string random_tag() {
    std::random_device device;
    const std::uint64_t bits = (std::uint64_t(device()) << 32) ^ device();
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bits));
    return text;
}

// Creates the temporary file ourselves, exclusively, without following a symlink, under a
// name of our PID and a random tag (two writers with one PID never meet on one name), and
// locks it; then checks that the name still is that file: a cleaner that took the unlocked
// file for stale in the moment before the lock removed it, and another name is tried.
int create_locked_temp(const fs::path& dir, const std::string& prefix, fs::path& temp) {
    for (int attempt = 0; attempt < 16; ++attempt) {
        temp = dir / (prefix + std::to_string(::getpid()) + "." + random_tag());
        const int fd =
            ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            return -1;
        }
        struct stat opened {
        }, named{};
        if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::fstat(fd, &opened) == 0 &&
            ::lstat(temp.c_str(), &named) == 0 && opened.st_ino == named.st_ino &&
            opened.st_dev == named.st_dev)
            return fd;
        ::close(fd);
    }
    errno = EEXIST;
    return -1;
}

// Devices, FIFOs and the like (/dev/null, /dev/stdout on a pipe) are written in place:
// renaming a file over them would replace the device node.
} // namespace

bool is_special_target(const fs::path& path) {
    std::error_code ec;
    const auto st = fs::status(path, ec);
    return !ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st);
}

void install_cleanup_handlers() {
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGSEGV, SIGABRT, SIGBUS, SIGFPE})
        std::signal(s, remove_temp_and_exit);
}

OutputBatch::OutputBatch() {
    if (g_pending) throw std::logic_error("OutputBatch: batches do not nest");
    g_pending = &pending_;
}

OutputBatch::~OutputBatch() {
    for (const auto& p : pending_) discard(p);
    g_pending = nullptr;
}

void OutputBatch::commit() {
    g_pending = nullptr;
    // Everything was written; only renames are left, the step that cannot run out of space.
    // A failed rename discards its own temporary; the ones not yet renamed stay for the
    // destructor to remove.
    std::size_t done = 0;
    try {
        for (; done < pending_.size(); ++done) rename_into_place(pending_[done]);
    } catch (...) {
        pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(done) + 1);
        throw;
    }
    pending_.clear();
}

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& fill) {
    fs::path target = path;
    // An output given as a symlink is written where the link points (the link stays).
    std::error_code link_ec;
    if (fs::is_symlink(fs::symlink_status(target, link_ec))) {
        const auto resolved = fs::weakly_canonical(target, link_ec);
        if (!link_ec) target = resolved;
    }
    if (is_special_target(target)) {
        fill(target);
        return;
    }
    fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (!fs::is_directory(dir))
        throw FormatError(path.string() + ": cannot write: folder '" + dir.string() +
                          "' does not exist");
    std::string prefix = "."; // built by appending: GCC 12 warns falsely on "x" + string&&
    prefix += target.filename().string();
    prefix += ".tmp.";
    // Two outputs of one batch never share a target.
    if (g_pending)
        for (const auto& p : *g_pending)
            if (p.target == target) throw FormatError(path.string() + ": written twice in one run");
    remove_stale_temps(dir, prefix);
    fs::path temp;
    int fd = create_locked_temp(dir, prefix, temp);
    if (fd < 0)
        throw WriteError(path.string() + ": cannot create a temporary file in " + dir.string() +
                         ": " + std::strerror(errno));
    // Replacing a file keeps its permission bits (a private 0600 output stays private, written
    // directly or through a link to it); a new file gets 0666 less the umask.
    struct stat existing {};
    if (::stat(target.c_str(), &existing) == 0 && S_ISREG(existing.st_mode))
        ::fchmod(fd, existing.st_mode & 07777);
    const auto temp_text = temp.string();
    const std::size_t slot = register_temp(temp_text);
    try {
        fill(temp);
        ::close(fd);
        fd = -1;
        PendingOutput pending{temp, target, slot};
        if (g_pending)
            g_pending->push_back(std::move(pending));
        else
            rename_into_place(pending);
    } catch (...) {
        if (fd >= 0) ::close(fd);
        discard(PendingOutput{temp, target, slot});
        throw;
    }
}

// fsync makes a regular file durable before the rename; devices (/dev/null) refuse it.
static bool sync_if_regular(int fd) {
    struct stat st {};
    return ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || ::fsync(fd) == 0;
}

void write_file(const fs::path& path, Header header, const BodyWriter& body) {
    header.version = header.version ? header.version : kind_version(header.kind);
    header.body_size = body.size();
    header.body_hash = "xxh64:" + hash_hex(body.hash());
    const auto head = serialise_header(header);
    // Readers refuse a header above kMaxHeaderBytes: writing one would make a file that no
    // tool can open.
    if (head.size() > kMaxHeaderBytes)
        throw FormatError(path.string() + ": not written: its header would be " +
                          std::to_string(head.size()) + " bytes, more than the " +
                          std::to_string(kMaxHeaderBytes) +
                          " readers accept (the command line and provenance are recorded "
                          "there: pass fewer or shorter arguments)");
    write_atomically(path, [&](const fs::path& temp) {
        std::FILE* f = std::fopen(temp.c_str(), "wb");
        if (!f)
            throw WriteError(path.string() + ": cannot open for writing: " + std::strerror(errno));
        bool ok = std::fwrite(head.data(), 1, head.size(), f) == head.size();
        body.for_each_piece([&](const std::byte* data, std::size_t size) {
            ok = ok && std::fwrite(data, 1, size, f) == size;
        });
        ok = ok && std::fflush(f) == 0 && sync_if_regular(fileno(f));
        ok = (std::fclose(f) == 0) && ok;
        if (!ok) throw WriteError(path.string() + ": write failed: " + std::strerror(errno));
    });
}

// ---- reading ----

static std::uint64_t parse_u64(const std::string& text, const std::string& path, const char* what) {
    std::uint64_t value = 0;
    std::size_t used = 0;
    try {
        value = std::stoull(text, &used);
    } catch (...) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw FormatError(path + ": corrupt header: bad " + std::string(what) + " '" + text + "'");
    return value;
}

struct ParsedHeader {
    Header header;
    std::size_t body_offset = 0;
};

static ParsedHeader parse_header(std::string_view bytes, const std::string& path,
                                 std::uint64_t file_size) {
    if (bytes.size() < kMagic.size() && kMagic.substr(0, bytes.size()) == bytes)
        throw FormatError(path + ": truncated: the file ends inside its magic line");
    if (bytes.substr(0, kMagic.size()) != kMagic)
        throw FormatError(path + ": not a radiosity file (wrong magic; expected '" +
                          std::string(kMagic) + "')");
    const auto end = bytes.find("\n\n");
    if (end == std::string_view::npos)
        throw FormatError(path + ": truncated or corrupt header (no end of header found)");
    const std::string_view text = bytes.substr(0, end + 1);
    const auto hash_pos = text.rfind("header_hash=");
    if (hash_pos == std::string_view::npos)
        throw FormatError(path + ": corrupt header: no header_hash line");
    const auto covered = text.substr(0, hash_pos);
    const auto stored = std::string(text.substr(hash_pos + 12, end - hash_pos - 12));
    if (stored != "xxh64:" + hash_hex(hash_bytes(covered.data(), covered.size())))
        throw FormatError(path +
                          ": corrupt header: checksum mismatch (the file was modified or damaged)");

    ParsedHeader parsed;
    Header& h = parsed.header;
    std::istringstream lines{std::string(covered)};
    std::string line;
    std::getline(lines, line);
    const auto container_version = line.substr(kMagic.size());
    if (container_version != (std::string(" ") += std::to_string(kContainerVersion)))
        throw FormatError(path + ": unsupported container version '" + container_version.substr(1) +
                          "' (this build reads version " + std::to_string(kContainerVersion) + ")");
    bool have_kind = false;
    while (std::getline(lines, line)) {
        const auto eq = line.find('=');
        if (eq == std::string::npos)
            throw FormatError(path + ": corrupt header line '" + line + "'");
        const auto key = line.substr(0, eq);
        const auto value = line.substr(eq + 1);
        if (key == "kind") {
            if (!parse_kind(value, h.kind))
                throw FormatError(path + ": unknown file kind '" + value + "'");
            have_kind = true;
        } else if (key == "version") {
            h.version = static_cast<std::uint32_t>(parse_u64(value, path, "version"));
        } else if (key == "tool") {
            h.tool = unescape(value);
        } else if (key == "command") {
            h.command = unescape(value);
        } else if (key == "provenance") {
            h.provenance.push_back(unescape(value));
        } else if (key == "input") {
            const auto space = value.find(' ');
            if (space == std::string::npos) throw FormatError(path + ": corrupt input line");
            h.inputs.push_back({unescape(value.substr(space + 1)), value.substr(0, space)});
        } else if (key.rfind("field.", 0) == 0) {
            h.fields.emplace_back(key.substr(6), unescape(value));
        } else if (key == "body_size") {
            h.body_size = parse_u64(value, path, "body size");
        } else if (key == "body_hash") {
            h.body_hash = value;
        } else {
            throw FormatError(path + ": corrupt header: unknown key '" + key + "'");
        }
    }
    if (!have_kind) throw FormatError(path + ": corrupt header: no kind");
    if (h.version > kind_version(h.kind) || h.version < kind_info(h.kind).oldest_version) {
        const auto& info = kind_info(h.kind);
        const std::string reads = info.oldest_version == info.version
                                      ? "version " + std::to_string(info.version)
                                      : "versions " + std::to_string(info.oldest_version) + " to " +
                                            std::to_string(info.version);
        throw FormatError(path + ": " + std::string(kind_name(h.kind)) + " format version " +
                          std::to_string(h.version) + " is not supported (this build reads " +
                          reads + "): write it again with this build's tools");
    }
    parsed.body_offset = (end + 2 + kBodyAlignment - 1) / kBodyAlignment * kBodyAlignment;
    // The padding after the header is zeros, as the writer leaves it (no other bytes hide
    // there unchecked).
    for (std::size_t k = end + 2; k < std::min<std::size_t>(parsed.body_offset, bytes.size()); ++k)
        if (bytes[k] != '\0')
            throw FormatError(path + ": corrupt: non-zero padding between the header and the " +
                              "body at byte " + std::to_string(k));
    const auto expected = parsed.body_offset + h.body_size;
    if (file_size < expected)
        throw FormatError(path + ": truncated: expected " + std::to_string(expected) +
                          " bytes, found " + std::to_string(file_size));
    if (file_size > expected)
        throw FormatError(path + ": corrupt: " + std::to_string(file_size - expected) +
                          " unexpected bytes after the body");
    return parsed;
}

static std::string read_prefix(std::ifstream& in, std::uint64_t file_size) {
    std::string prefix(std::min<std::uint64_t>(file_size, kMaxHeaderBytes), '\0');
    in.read(prefix.data(), static_cast<std::streamsize>(prefix.size()));
    return prefix;
}

static void check_kind(const Header& h, const std::string& path, const Kind* expected) {
    if (expected && h.kind != *expected)
        throw FormatError(path + ": is a " + std::string(kind_description(h.kind)) + " (" +
                          std::string(kind_name(h.kind)) + ") file, but a " +
                          std::string(kind_description(*expected)) + " (" +
                          std::string(kind_name(*expected)) + ") file was expected");
}

static std::uint64_t open_sized(std::ifstream& in, const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw FormatError(path.string() + ": is a folder, not a file");
    // Opening a FIFO blocks until something writes to it: a chain file is a regular file.
    const auto status = fs::status(path, ec);
    if (!ec && fs::exists(status) && !fs::is_regular_file(status))
        throw FormatError(path.string() +
                          ": is not a regular file (a FIFO, socket or device): give a chain file");
    in.open(path, std::ios::binary);
    if (!in)
        throw FormatError(path.string() + ": cannot open for reading (" + std::strerror(errno) +
                          ")");
    const auto size = fs::file_size(path, ec);
    if (ec) throw FormatError(path.string() + ": cannot read size: " + ec.message());
    if (size == 0) throw FormatError(path.string() + ": is empty (truncated)");
    return size;
}

Header read_header(const fs::path& path, const Kind* expected) {
    std::ifstream in;
    const auto size = open_sized(in, path);
    auto header = parse_header(read_prefix(in, size), path.string(), size).header;
    check_kind(header, path.string(), expected);
    return header;
}

// ---- streaming body reader ----

namespace {
XXH64_state_t* new_hash_state() {
    auto* state = XXH64_createState();
    if (!state) throw std::bad_alloc();
    XXH64_reset(state, 0);
    return state;
}
} // namespace

BodyReader::BodyReader(const fs::path& path, const Kind* expected) : path_(path.string()) {
    std::ifstream in;
    const auto size = open_sized(in, path);
    const auto prefix = read_prefix(in, size);
    auto parsed = parse_header(prefix, path_, size);
    check_kind(parsed.header, path_, expected);
    header_ = std::move(parsed.header);
    in.close();
    file_ = std::fopen(path_.c_str(), "rb");
    if (!file_)
        throw FormatError(path_ + ": cannot open for reading (" + std::strerror(errno) + ")");
    body_state_ = new_hash_state();
    file_state_ = new_hash_state();
    // The whole file's hash covers the header and its padding, then the body.
    auto* file_state = static_cast<XXH64_state_t*>(file_state_);
    const std::size_t head = std::min<std::size_t>(parsed.body_offset, prefix.size());
    XXH64_update(file_state, prefix.data(), head);
    if (parsed.body_offset > head) { // a header at the 1 MiB limit: the rest of its padding
        std::string gap(parsed.body_offset - head, '\0');
        if (std::fseek(file_, static_cast<long>(head), SEEK_SET) != 0 ||
            std::fread(gap.data(), 1, gap.size(), file_) != gap.size())
            throw FormatError(path_ + ": truncated header padding");
        if (gap.find_first_not_of('\0') != std::string::npos)
            throw FormatError(path_ + ": corrupt: non-zero padding between the header and the " +
                              "body at byte " + std::to_string(head + gap.find_first_not_of('\0')));
        XXH64_update(file_state, gap.data(), gap.size());
    }
    if (std::fseek(file_, static_cast<long>(parsed.body_offset), SEEK_SET) != 0)
        throw FormatError(path_ + ": cannot seek to the body (" + std::strerror(errno) + ")");
}

BodyReader::~BodyReader() {
    if (file_) std::fclose(file_);
    XXH64_freeState(static_cast<XXH64_state_t*>(body_state_));
    XXH64_freeState(static_cast<XXH64_state_t*>(file_state_));
}

void BodyReader::read(void* into, std::uint64_t bytes) {
    // In blocks, each hashed while it is still in the cache.
    auto* out = static_cast<unsigned char*>(into);
    constexpr std::uint64_t kBlock = std::uint64_t(4) << 20;
    for (std::uint64_t done = 0; done < bytes;) {
        const auto want = static_cast<std::size_t>(std::min(kBlock, bytes - done));
        if (std::fread(out + done, 1, want, file_) != want)
            throw FormatError(path_ + ": truncated body (the file shrank while it was read)");
        XXH64_update(static_cast<XXH64_state_t*>(body_state_), out + done, want);
        XXH64_update(static_cast<XXH64_state_t*>(file_state_), out + done, want);
        done += want;
    }
    pos_ += bytes;
}

void BodyReader::check_checksum() {
    checked_ = true;
    const auto hash = "xxh64:" + hash_hex(XXH64_digest(static_cast<XXH64_state_t*>(body_state_)));
    if (hash != header_.body_hash)
        throw FormatError(path_ +
                          ": corrupt body: checksum mismatch (the file was modified or damaged)");
    header_.file_hash = "xxh64:" + hash_hex(XXH64_digest(static_cast<XXH64_state_t*>(file_state_)));
}

void BodyReader::fail(const std::string& message) {
    // A value found wrong before the checksum was checked may be damage: read the rest, and
    // report the mismatch if there is one.
    if (!checked_) {
        std::vector<unsigned char> rest(
            static_cast<std::size_t>(std::min<std::uint64_t>(header_.body_size - pos_, 4 << 20)));
        while (pos_ < header_.body_size)
            read(rest.data(), std::min<std::uint64_t>(rest.size(), header_.body_size - pos_));
        check_checksum();
    }
    throw FormatError(path_ + ": corrupt body: " + message);
}

void BodyReader::align() {
    const auto next = std::min(header_.body_size, (pos_ + 7) / 8 * 8);
    if (next == pos_) return;
    unsigned char pad[8];
    const auto size = next - pos_;
    read(pad, size);
    // Padding is zero: a writer never leaves anything else there.
    for (std::uint64_t k = 0; k < size; ++k)
        if (pad[k] != 0) fail("non-zero padding at body offset " + std::to_string(next - size + k));
}

void BodyReader::need(std::uint64_t bytes, const char* what) {
    if (bytes > header_.body_size - pos_)
        fail(std::string(what) + " needs " + std::to_string(bytes) + " bytes but only " +
             std::to_string(header_.body_size - pos_) + " remain");
}

std::uint64_t BodyReader::u64() {
    align();
    need(8, "an integer");
    unsigned char raw[8];
    read(raw, 8);
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i) value |= std::uint64_t(raw[i]) << (8 * i);
    return value;
}

std::string BodyReader::string() {
    const auto size = count(1, "a string");
    std::string text(size, '\0');
    read(text.data(), size);
    align();
    return text;
}

std::uint64_t BodyReader::count(std::size_t element_size, const char* what) {
    const auto value = u64();
    const auto remaining = header_.body_size - pos_;
    if (element_size && value > remaining / element_size)
        fail(std::string("count of ") + what + " (" + std::to_string(value) +
             ") exceeds the body size");
    return value;
}

void BodyReader::expect_end() {
    align();
    if (pos_ != header_.body_size)
        fail(std::to_string(header_.body_size - pos_) + " unexpected bytes after the data");
    if (!checked_) check_checksum();
}

} // namespace radfmt
