#include "radfmt/names.hpp"

#include <cstdio>

namespace radfmt {
namespace {
// The length of the UTF-8 sequence at text[at] (its bytes checked), or 0 when there is none.
std::size_t utf8_length(std::string_view text, std::size_t at) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = byte(at);
    std::size_t n = c < 0x80           ? 1
                    : (c >> 5) == 0x6  ? 2
                    : (c >> 4) == 0xE  ? 3
                    : (c >> 3) == 0x1E ? 4
                                       : 0;
    if (n == 0 || at + n > text.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((byte(at + k) & 0xC0) != 0x80) return 0;
    // Overlong forms and surrogates are not UTF-8.
    if (n == 2 && c < 0xC2) return 0;
    if (n == 3 && ((c == 0xE0 && byte(at + 1) < 0xA0) || (c == 0xED && byte(at + 1) >= 0xA0)))
        return 0;
    if (n == 4 &&
        ((c == 0xF0 && byte(at + 1) < 0x90) || c > 0xF4 || (c == 0xF4 && byte(at + 1) >= 0x90)))
        return 0;
    return n;
}

bool control(unsigned char c) {
    return c < 0x20 || c == 0x7F;
}
} // namespace

std::string name_problem(std::string_view name) {
    if (name.empty()) return "an empty name";
    if (name.size() > kMaxNameBytes)
        return "a name of " + std::to_string(name.size()) + " bytes (at most " +
               std::to_string(kMaxNameBytes) + ")";
    for (std::size_t i = 0; i < name.size();) {
        const auto n = utf8_length(name, i);
        if (n == 0) return "a name that is not UTF-8 text (byte " + std::to_string(i) + ")";
        if (n == 1 && control(static_cast<unsigned char>(name[i])))
            return "a name holding a control character (a newline, tab or the like)";
        i += n;
    }
    return "";
}

std::string clean_name(std::string_view name) {
    std::string out;
    for (std::size_t i = 0; i < name.size();) {
        const auto n = utf8_length(name, i);
        std::string piece;
        if (n == 0) { // Latin-1: U+0080..U+00FF as two bytes
            const unsigned char c = static_cast<unsigned char>(name[i]);
            piece = {static_cast<char>(0xC0 | (c >> 6)), static_cast<char>(0x80 | (c & 0x3F))};
            i += 1;
        } else if (n == 1 && control(static_cast<unsigned char>(name[i]))) {
            piece = "?";
            i += 1;
        } else {
            piece = std::string(name.substr(i, n));
            i += n;
        }
        if (out.size() + piece.size() > kMaxNameBytes) break;
        out += piece;
    }
    return out.empty() ? "unnamed" : out;
}

std::string shown_name(std::string_view name) {
    std::string out;
    char hex[8];
    for (std::size_t i = 0; i < name.size() && out.size() < 40;) {
        const auto n = utf8_length(name, i);
        const unsigned char c = static_cast<unsigned char>(name[i]);
        if (n == 0 || (n == 1 && control(c))) {
            std::snprintf(hex, sizeof hex, "\\x%02X", c);
            out += c == '\n'   ? std::string("\\n")
                   : c == '\t' ? std::string("\\t")
                               : std::string(hex);
            i += 1;
        } else {
            out.append(name.substr(i, n));
            i += n;
        }
    }
    return out.size() < name.size() || out.size() >= 40 ? out + "..." : out;
}

} // namespace radfmt
