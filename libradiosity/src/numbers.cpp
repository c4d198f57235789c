#include "radiosity/numbers.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <unistd.h>

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
