#include "photometry/text_lines.hpp"

#include "radiosity/text_input.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rad::photometry {

std::string quoted(std::string_view text) {
    return quoted_prefix(text);
}

std::string_view plain_text(std::string_view text, const std::string& name) {
    if (text.starts_with("\xEF\xBB\xBF")) return text.substr(3);
    const bool wide = text.starts_with("\xFF\xFE") || text.starts_with("\xFE\xFF") ||
                      text.substr(0, 4096).find('\0') != std::string_view::npos;
    if (wide)
        throw InputError(FileLoc{name, 1}, "is UTF-16 or UTF-32 text (a byte-order mark or NUL "
                                           "bytes): save it as UTF-8 or ASCII");
    return text;
}

std::vector<std::string_view> split_lines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t start = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '\n' && text[i] != '\r') continue;
        lines.push_back(text.substr(start, i - start));
        if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
        start = i + 1;
    }
    if (start < text.size()) lines.push_back(text.substr(start));
    return lines;
}

bool csv_quote_open(std::string_view text) {
    return std::count(text.begin(), text.end(), '"') % 2 == 1;
}

void unclosed_csv_quote(const FileLoc& opened) {
    throw InputError(opened, "a double quote opened on this line is never closed (the quoted "
                             "field runs to the end of the file): close it, or write a quote "
                             "inside a field as two (\"\")");
}

std::vector<std::string> csv_fields(std::string_view line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (c == '"') {
            if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
                out.back() += '"';
                ++i;
            } else {
                quoted = !quoted;
            }
        } else if (c == ',' && !quoted) {
            out.emplace_back();
        } else {
            out.back() += c;
        }
    }
    for (auto& f : out) {
        while (!f.empty() && (f.front() == ' ' || f.front() == '\t')) f.erase(f.begin());
        while (!f.empty() && (f.back() == ' ' || f.back() == '\t')) f.pop_back();
    }
    return out;
}

bool parse_number(std::string_view token, double& value) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    // "69." and ".5" are numbers in these files; from_chars takes both.
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    return error == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

TokenCursor::TokenCursor(std::vector<std::string_view> lines, std::size_t first_line,
                         std::string file)
    : lines_(std::move(lines)), line_(first_line), file_(std::move(file)) {}

bool TokenCursor::next_token(std::string_view& token) {
    const auto separator = [](char c) {
        return c == ' ' || c == '\t' || c == ',' || c == '\f' || c == '\v';
    };
    while (line_ < lines_.size()) {
        const auto& line = lines_[line_];
        while (pos_ < line.size() && separator(line[pos_])) ++pos_;
        if (pos_ < line.size()) {
            const auto start = pos_;
            while (pos_ < line.size() && !separator(line[pos_])) ++pos_;
            token = line.substr(start, pos_ - start);
            return true;
        }
        ++line_;
        pos_ = 0;
    }
    return false;
}

double TokenCursor::number(const std::string& what) {
    std::string_view token;
    if (!next_token(token)) fail("the file ends where " + what + " should be (truncated?)");
    double value = 0;
    if (!parse_number(token, value)) fail("expected " + what + ", found " + quoted(token));
    return value;
}

long TokenCursor::count(const std::string& what, long low, long high) {
    const double value = number(what);
    if (value != std::floor(value) || value < double(low) || value > double(high))
        fail(what + " must be a whole number from " + std::to_string(low) + " to " +
             std::to_string(high) + ", not " + std::to_string(value));
    return static_cast<long>(value);
}

bool TokenCursor::at_end() {
    std::string_view token;
    const auto line = line_;
    const auto pos = pos_;
    const bool more = next_token(token);
    if (more) {
        // Put the token back: at_end only looks.
        line_ = line;
        pos_ = pos;
    }
    return !more;
}

void TokenCursor::fail(const std::string& message) const {
    throw InputError(where(), message);
}

double checked_candela(double value, double scale, const TokenCursor& in) {
    const double cd = value * scale;
    if (std::isfinite(cd) && cd <= kMaxCandela) return cd;
    char text[300];
    std::snprintf(text, sizeof text,
                  "an intensity of %.4g times the file's multipliers %.4g is %.4g cd, more than "
                  "the %.0e cd no luminaire reaches: check the candela multiplier (IES) or the "
                  "conversion factor and lamp flux (LDT)",
                  value, scale, cd, kMaxCandela);
    in.fail(text);
}

} // namespace rad::photometry
