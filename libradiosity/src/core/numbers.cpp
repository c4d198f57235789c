#include "radiosity/numbers.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

namespace rad {

namespace {
bool is_digit(char c) {
    return c >= '0' && c <= '9';
}
} // namespace

bool parse_number(std::string_view text, double& value) {
    // Check the grammar by hand first: from_chars alone would accept "inf", "nan" and
    // "infinity", and stops quietly before hex ("0x2" reads as 0).
    std::size_t pos = 0;
    const std::size_t n = text.size();
    if (pos < n && (text[pos] == '+' || text[pos] == '-')) ++pos;
    std::size_t digits = 0;
    while (pos < n && is_digit(text[pos])) ++pos, ++digits;
    if (pos < n && text[pos] == '.') {
        ++pos;
        while (pos < n && is_digit(text[pos])) ++pos, ++digits;
    }
    if (digits == 0) return false;
    if (pos < n && (text[pos] == 'e' || text[pos] == 'E')) {
        ++pos;
        if (pos < n && (text[pos] == '+' || text[pos] == '-')) ++pos;
        std::size_t exponent_digits = 0;
        while (pos < n && is_digit(text[pos])) ++pos, ++exponent_digits;
        if (exponent_digits == 0) return false;
    }
    if (pos != n) return false;
    // from_chars takes no leading '+': skip it (the grammar above allowed one sign only).
    const char* begin = text.data() + (text[0] == '+' ? 1 : 0);
    double parsed = 0;
    const auto [end, ec] = std::from_chars(begin, text.data() + n, parsed);
    if (ec != std::errc() || end != text.data() + n || !std::isfinite(parsed)) return false;
    value = parsed;
    return true;
}

bool parse_count(std::string_view text, std::uint64_t& value) {
    if (text.empty() || text.size() > 15) return false;
    std::uint64_t v = 0;
    for (const char c : text) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + std::uint64_t(c - '0');
    }
    value = v;
    return true;
}

bool spells_non_finite(std::string_view text) {
    std::string lower;
    for (char c : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!lower.empty() && (lower[0] == '+' || lower[0] == '-')) lower.erase(0, 1);
    return lower == "nan" || lower == "inf" || lower == "infinity" || lower.rfind("nan(", 0) == 0;
}

std::uint64_t physical_memory_bytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page_size = ::sysconf(_SC_PAGE_SIZE);
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

namespace {
// A cgroup limit file's value in bytes ("max", a missing file, or nonsense: none).
std::optional<std::uint64_t> cgroup_limit(const std::string& file) {
    std::ifstream in(file);
    std::string text;
    if (!(in >> text) || text == "max") return std::nullopt;
    std::uint64_t value = 0;
    if (!parse_count(text, value)) return std::nullopt;
    return value;
}

// The least memory limit of the cgroups this process is in, and of every cgroup above each
// (a parent's limit binds its children): cgroup v2's memory.max and v1's
// memory.limit_in_bytes, under the hierarchies' usual mount points. A container may mount its
// own cgroup as the root, so the root's own file is read too.
std::optional<std::uint64_t> cgroup_memory_limit() {
    std::ifstream in("/proc/self/cgroup");
    std::optional<std::uint64_t> least;
    auto consider = [&](const std::string& file) {
        if (const auto v = cgroup_limit(file); v && (!least || *v < *least)) least = v;
    };
    for (std::string line; std::getline(in, line);) {
        // "0::/path" (v2) or "4:memory:/path" (v1)
        const auto first = line.find(':'), second = line.find(':', first + 1);
        if (first == std::string::npos || second == std::string::npos) continue;
        const auto controllers = line.substr(first + 1, second - first - 1);
        std::string path = line.substr(second + 1);
        std::vector<std::string> roots;
        std::string name;
        if (controllers.empty())
            roots = {"/sys/fs/cgroup", "/sys/fs/cgroup/unified"}, name = "memory.max";
        else if (controllers.find("memory") != std::string::npos)
            roots = {"/sys/fs/cgroup/memory"}, name = "memory.limit_in_bytes";
        else
            continue;
        // "/a/b", then "/a", then "" (the root)
        while (!path.empty() && path.back() == '/') path.pop_back();
        for (const auto& root : roots)
            for (std::string p = path;; p = p.substr(0, std::min(p.size(), p.rfind('/')))) {
                consider(root + p + "/" + name);
                if (p.empty() || p.find('/') == std::string::npos) break;
            }
    }
    return least;
}
} // namespace

std::uint64_t job_memory_bytes(std::string* source) {
    std::uint64_t bytes = physical_memory_bytes();
    if (source) *source = "physical memory";
    if (const auto limit = cgroup_memory_limit(); limit && *limit < bytes) {
        bytes = *limit;
        if (source) *source = "the job's cgroup memory limit";
    }
    rlimit address{};
    if (::getrlimit(RLIMIT_AS, &address) == 0 && address.rlim_cur != RLIM_INFINITY &&
        address.rlim_cur < bytes) {
        bytes = address.rlim_cur;
        if (source) *source = "the address-space limit (ulimit -v)";
    }
    return bytes;
}

std::string human_bytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int unit = 0;
    while (bytes >= 1024 && unit < 6) {
        bytes /= 1024;
        ++unit;
    }
    char text[64];
    std::snprintf(text, sizeof text, "%.1f %s", bytes, units[unit]);
    return text;
}

} // namespace rad
