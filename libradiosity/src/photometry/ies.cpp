// IES LM-63 (1986, 1991, 1995, 2002, 2019): keywords, the TILT block (NONE, INCLUDE or a
// file), the numbers, the angles and the candela, into a photometric web.
#include "photometry/text_lines.hpp"
#include "photometry/web.hpp"
#include "radiosity/photometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rad {
using photometry::TokenCursor;

namespace {
constexpr double kFoot = 0.3048;
constexpr double kMaxOpeningMetres = 1000;

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

// The edition from the first line; `first_keyword_line` is where keywords start.
std::string edition_of(std::string_view first, std::size_t& first_keyword_line) {
    first = trim(first);
    first_keyword_line = 1;
    if (first.starts_with("IESNA:LM-63-") || first.starts_with("IES:LM-63-"))
        return std::string(first.substr(first.find(':') + 1));
    if (first.starts_with("IESNA91")) return "LM-63-1991";
    first_keyword_line = 0; // 1986: no identifier line
    return "LM-63-1986";
}

// The keyword lines up to the TILT line; returns the TILT line's index.
std::size_t read_keywords(const std::vector<std::string_view>& lines, std::size_t from,
                          Photometry& p) {
    for (std::size_t i = from; i < lines.size(); ++i) {
        const auto line = trim(lines[i]);
        if (line.starts_with("TILT=") || line.starts_with("TILT =")) return i;
        if (!line.starts_with('[')) continue; // free text (1986) or a stray line: kept out
        const auto close = line.find(']');
        if (close == std::string_view::npos) continue;
        const std::string key(line.substr(1, close - 1));
        const std::string value(trim(line.substr(close + 1)));
        if (key == "MORE" && !p.keywords.empty())
            p.keywords.back().second += "\n" + value;
        else
            p.keywords.emplace_back(key, value);
    }
    throw InputError(FileLoc{p.source, int(lines.size())},
                     "no TILT= line: an LM-63 file has TILT=NONE, TILT=INCLUDE or TILT=<file> "
                     "after its keywords, before its numbers");
}

// The numbers of a TILT block (from the photometric file or a TILT file).
TiltTable read_tilt_numbers(TokenCursor& in) {
    TiltTable tilt;
    tilt.geometry = int(in.count("the TILT lamp-to-luminaire geometry (1, 2 or 3)", 1, 3));
    const long n = in.count("the number of TILT angles", 1, 10000);
    for (long k = 0; k < n; ++k) tilt.angles.push_back(in.number("a TILT angle"));
    for (long k = 0; k < n; ++k) {
        const double f = in.number("a TILT multiplier");
        if (f < 0) in.fail("a TILT multiplier is negative (" + std::to_string(f) + ")");
        if (f > photometry::kMaxTiltFactor) {
            char text[160];
            std::snprintf(text, sizeof text,
                          "a TILT multiplier of %.4g: tilt factors scale the output around 1 "
                          "(at most %.0f here)",
                          f, photometry::kMaxTiltFactor);
            in.fail(text);
        }
        tilt.factors.push_back(f);
    }
    for (std::size_t k = 1; k < tilt.angles.size(); ++k)
        if (!(tilt.angles[k] > tilt.angles[k - 1])) in.fail("TILT angles must increase");
    if (tilt.angles.front() < 0 || tilt.angles.back() > 180)
        in.fail("TILT angles lie within 0 to 180 degrees");
    return tilt;
}

// The TILT line's table: none, the INCLUDE block read from `in` (which then stands after it),
// or the named file's.
TiltTable read_tilt(std::string_view tilt_line_text, const FileLoc& where, TokenCursor& in,
                    const IncludeReader& read_include) {
    const auto line = trim(tilt_line_text);
    const std::string value(trim(line.substr(line.find('=') + 1)));
    if (value == "NONE") return {};
    if (value == "INCLUDE") return read_tilt_numbers(in);
    if (value.empty()) throw InputError(where, "TILT= names nothing (NONE, INCLUDE or a file)");
    if (!read_include)
        throw InputError(where, "TILT=" + value + " names a file, which cannot be read here");
    const std::string text = read_include(value, where);
    TokenCursor tilt_in(photometry::split_lines(text), 0, value);
    return read_tilt_numbers(tilt_in);
}

struct IesHead {
    double lamps = 1, lumens = 0, multiplier = 1;
    long nv = 0, nh = 0;
    int type = 1, units = 2;
    double width = 0, length = 0, height = 0;
    double ballast = 1, ballast_lamp = 1, watts = 0;
};

IesHead read_head(TokenCursor& in, const std::string& edition) {
    IesHead h;
    h.lamps = double(in.count("the number of lamps", 1, 1000000));
    h.lumens = in.number("the lumens per lamp");
    if (!(h.lumens > 0 || h.lumens == -1))
        in.fail("lumens per lamp must be positive, or -1 for absolute photometry (it is " +
                std::to_string(h.lumens) + ")");
    h.multiplier = in.number("the candela multiplier");
    if (!(h.multiplier > 0)) in.fail("the candela multiplier must be positive");
    h.nv = in.count("the number of vertical angles", 2, 100000);
    h.nh = in.count("the number of horizontal angles", 1, 100000);
    if (double(h.nv) * double(h.nh) > 1e7)
        in.fail("more than 10 million candela values: not a photometric file");
    h.type = int(in.count("the photometric type (1 = C, 2 = B, 3 = A)", 1, 3));
    h.units = int(in.count("the units type (1 = feet, 2 = metres)", 1, 2));
    // An opening over 1 km (a 1e300 m one was drawn and sampled) is no luminaire's.
    const double to_metres = h.units == 1 ? kFoot : 1;
    const auto opening = [&](const char* what) {
        const double v = in.number(what);
        if (!(std::abs(v) * to_metres <= kMaxOpeningMetres)) {
            char text[64];
            std::snprintf(text, sizeof text, " (it is %g %s)", v, h.units == 1 ? "ft" : "m");
            in.fail(std::string(what) + " is over 1000 m: not a luminaire's" + text);
        }
        return v;
    };
    h.width = opening("the luminous opening's width");
    h.length = opening("the luminous opening's length");
    h.height = opening("the luminous opening's height");
    h.ballast = in.number("the ballast factor");
    if (!(h.ballast > 0)) in.fail("the ballast factor must be positive");
    // 1991 and 1995 have the ballast-lamp photometric factor here; later editions a field for
    // future use (2019: the file generation type), which scales nothing.
    const double factor = in.number("the ballast-lamp photometric factor or future-use field");
    if (edition == "LM-63-1991" || edition == "LM-63-1995" || edition == "LM-63-1986")
        h.ballast_lamp = factor > 0 ? factor : 1;
    h.watts = in.number("the input watts");
    return h;
}

// `count` angles, each larger than the one before.
std::vector<double> read_angles(TokenCursor& in, long count, const std::string& what) {
    std::vector<double> out;
    for (long k = 0; k < count; ++k) {
        out.push_back(in.number("a " + what + " angle"));
        if (k > 0 && !(out[std::size_t(k)] > out[std::size_t(k) - 1]))
            in.fail(what + " angles must increase: " + std::to_string(out[std::size_t(k) - 1]) +
                    " is followed by " + std::to_string(out[std::size_t(k)]));
    }
    return out;
}
} // namespace

Photometry parse_ies(std::string_view text, const std::string& name,
                     const IncludeReader& read_include) {
    text = photometry::plain_text(text, name);
    Photometry p;
    p.source = name;
    const auto lines = photometry::split_lines(text);
    if (lines.empty()) throw InputError(FileLoc{name, 0}, "empty file: not an IES file");
    std::size_t first_keyword = 0;
    p.edition = edition_of(lines.front(), first_keyword);
    const auto tilt_line = read_keywords(lines, first_keyword, p);
    TokenCursor in(lines, tilt_line + 1, name);
    p.tilt = read_tilt(lines[tilt_line], FileLoc{name, int(tilt_line + 1)}, in, read_include);
    const auto head = read_head(in, p.edition);
    p.type = PhotometricType(head.type);
    p.v = read_angles(in, head.nv, "vertical");
    const auto h = read_angles(in, head.nh, "horizontal");
    const auto angles_end = in.where();
    const double scale = head.multiplier * head.ballast * head.ballast_lamp;
    std::vector<double> values;
    values.reserve(std::size_t(head.nv * head.nh));
    for (long k = 0; k < head.nv * head.nh; ++k) {
        const double cd = in.number("candela value " + std::to_string(k + 1) + " of " +
                                    std::to_string(head.nv * head.nh));
        if (cd < 0) in.fail("a negative candela value (" + std::to_string(cd) + ")");
        values.push_back(photometry::checked_candela(cd, scale, in));
    }
    if (!in.at_end()) {
        in.number("the end of the file");
        in.fail("numbers left over after " + std::to_string(head.nv) + " x " +
                std::to_string(head.nh) + " candela values: the counts do not match the values");
    }
    const photometry::Fail fail = [&](const std::string& m) { throw InputError(angles_end, m); };
    if (p.type == PhotometricType::C) {
        if (p.v.front() < 0 || p.v.back() > 180)
            fail("type C vertical angles lie within 0 to 180 degrees");
        photometry::complete_type_c(p, h, values, fail);
    } else {
        if (p.v.front() < -90 || p.v.back() > 90)
            fail("type A and B vertical angles lie within -90 to 90 degrees");
        photometry::complete_type_ab(p, h, values, fail);
    }
    p.lamp_lumens = head.lumens > 0 ? head.lamps * head.lumens : 0;
    p.input_watts = head.watts;
    for (const auto& [key, value] : p.keywords)
        if ((key == "_CRI" || key == "CRI") && p.colour_rendering.empty())
            p.colour_rendering = value;
    const double unit = head.units == 1 ? kFoot : 1;
    p.round = head.width < 0 || head.length < 0;
    p.length = std::max(std::abs(head.length), p.round ? std::abs(head.width) : 0.0) * unit;
    p.width = (p.round ? p.length / unit : std::abs(head.width)) * unit;
    p.height = std::abs(head.height) * unit;
    return p;
}

} // namespace rad
