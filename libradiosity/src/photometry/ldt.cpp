// EULUMDAT (.ldt): the fixed header lines, the lamp sets, the angles and the intensities of
// the C-planes its symmetry (Isym 0-4) stores, into a photometric web.
#include "photometry/text_lines.hpp"
#include "photometry/web.hpp"
#include "radiosity/photometry.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace rad {
using photometry::TokenCursor;

namespace {
// Header lines are one value each, read by their (1-based) line number.
class LdtLines {
  public:
    LdtLines(std::vector<std::string_view> lines, std::string name)
        : lines_(std::move(lines)), name_(std::move(name)) {}
    std::string_view text(std::size_t line, const std::string& what) const {
        if (line > lines_.size())
            throw InputError(FileLoc{name_, int(lines_.size())},
                             "the file ends where line " + std::to_string(line) + " (" + what +
                                 ") should be (truncated?)");
        return lines_[line - 1];
    }
    std::string trimmed_text(std::size_t line, const std::string& what) const {
        return std::string(trimmed(text(line, what)));
    }
    // A number, with a decimal comma taken as a point (some writers use one).
    double number(std::size_t line, const std::string& what) const {
        std::string token(trimmed(text(line, what)));
        if (token.find('.') == std::string::npos)
            std::replace(token.begin(), token.end(), ',', '.');
        double value = 0;
        if (!photometry::parse_number(token, value))
            throw InputError(FileLoc{name_, int(line)},
                             "expected " + what + ", found " + photometry::quoted(token));
        return value;
    }
    long count(std::size_t line, const std::string& what, long low, long high) const {
        const double value = number(line, what);
        if (value != std::floor(value) || value < double(low) || value > double(high))
            throw InputError(FileLoc{name_, int(line)}, what + " must be a whole number from " +
                                                            std::to_string(low) + " to " +
                                                            std::to_string(high));
        return long(value);
    }
    // A colour temperature on a line ("3000K", "nw/4200", "LED 4000 K"): its first number
    // within 1667 to 25000 K, 0 when there is none.
    double colour_temperature(std::size_t line) const {
        if (line > lines_.size()) return 0;
        const std::string text(lines_[line - 1]);
        for (std::size_t i = 0; i < text.size(); ++i) {
            if (!std::isdigit(static_cast<unsigned char>(text[i]))) continue;
            const double value = std::strtod(text.c_str() + i, nullptr);
            if (value >= 1667 && value <= 25000) return value;
            while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
        }
        return 0;
    }
    const std::vector<std::string_view>& all() const { return lines_; }
    const std::string& name() const { return name_; }

  private:
    static std::string_view trimmed(std::string_view s) {
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
        while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
        return s;
    }
    std::vector<std::string_view> lines_;
    std::string name_;
};

// The C-planes an Isym stores: their indices into the C angles.
std::vector<std::size_t> stored_planes(int isym, const std::vector<double>& c, TokenCursor& in) {
    const std::size_t mc = c.size();
    std::vector<std::size_t> out;
    const auto first_n = [&](std::size_t n, std::size_t from) {
        if (from + n > mc)
            in.fail("the C angles do not hold the planes Isym " + std::to_string(isym) + " stores");
        for (std::size_t k = 0; k < n; ++k) out.push_back(from + k);
    };
    switch (isym) {
    case 0:
        first_n(mc, 0);
        break;
    case 1:
        first_n(1, 0);
        break;
    case 2:
        first_n(mc / 2 + 1, 0);
        break;
    case 3: {
        const auto at90 = std::find(c.begin(), c.end(), 90.0);
        if (at90 == c.end()) in.fail("Isym 3 stores C90 to C270, but no C angle is 90");
        first_n(mc / 2 + 1, std::size_t(at90 - c.begin()));
        break;
    }
    default:
        first_n(mc / 4 + 1, 0);
        break;
    }
    return out;
}
} // namespace

Photometry parse_ldt(std::string_view text, const std::string& name) {
    text = photometry::plain_text(text, name);
    const LdtLines ldt(photometry::split_lines(text), name);
    Photometry p;
    p.source = name;
    p.edition = "EULUMDAT";
    const int isym = int(ldt.count(3, "Isym (the symmetry, 0 to 4)", 0, 4));
    const long mc = ldt.count(4, "Mc (the number of C-planes)", 1, 3600);
    const long ng = ldt.count(6, "Ng (the number of gamma angles)", 2, 3600);
    if (isym == 0 && mc < 2) throw InputError(FileLoc{name, 4}, "Isym 0 needs Mc of 2 or more");
    const double mm = 1e-3;
    // An area over 1 km (a 1e300 m one was drawn and sampled) is no luminaire's.
    const auto area_size = [&](std::size_t line, const char* what) {
        const double v = ldt.number(line, what);
        if (!(std::abs(v) * mm <= 1000))
            throw InputError(FileLoc{name, int(line)},
                             std::string(what) + " is over 1000 m: not a luminaire's");
        return v * mm;
    };
    p.length = area_size(16, "the luminous area's length or diameter (mm)");
    p.width = area_size(17, "the luminous area's width (mm)");
    p.round = p.width == 0;
    if (p.round) p.width = p.length;
    for (std::size_t line = 18; line <= 21; ++line)
        p.height = std::max(p.height, area_size(line, "a luminous area's height (mm)"));
    p.stated_downward_percent = ldt.number(22, "DFF (the downward flux fraction, %)");
    const double lorl = ldt.number(23, "LORL (the light output ratio, %)");
    const double cfli = ldt.number(24, "the conversion factor for luminous intensities");
    if (!(cfli > 0)) throw InputError(FileLoc{name, 24}, "the conversion factor must be positive");
    const long sets = ldt.count(26, "n (the number of lamp sets)", 1, 20);
    const auto set_line = [&](int field) { return std::size_t(27 + field * sets); };
    const double lamps = ldt.number(set_line(0), "the number of lamps of set 1");
    const double lamp_flux = ldt.number(set_line(2), "the lamp flux of set 1 (lm)");
    if (!(lamp_flux > 0))
        throw InputError(FileLoc{name, int(set_line(2))}, "the lamp flux must be positive");
    p.cct = ldt.colour_temperature(set_line(3));
    p.colour_rendering = ldt.trimmed_text(set_line(4), "the colour rendering of set 1");
    if (p.colour_rendering == "0" || p.colour_rendering == "-") p.colour_rendering.clear();
    p.input_watts = ldt.number(set_line(5), "the wattage of set 1 (W)");
    // The header's names, as IES keywords (what a report calls the luminaire): line 1 the
    // company, 9 the luminaire's name, 10 its number.
    for (const auto& [line, key] : {std::pair{std::size_t(1), "MANUFAC"},
                                    {std::size_t(9), "LUMINAIRE"},
                                    {std::size_t(10), "LUMCAT"}}) {
        auto value = ldt.trimmed_text(line, key);
        if (!value.empty()) p.keywords.emplace_back(key, std::move(value));
    }
    // A negative lamp count marks absolute photometry: the flux is then the luminaire's.
    p.lamp_lumens = lamps < 0 ? 0 : lamp_flux;
    p.stated_flux = lamp_flux * (lamps < 0 ? 1 : lorl / 100);

    TokenCursor in(ldt.all(), set_line(6) - 1, name); // from 0
    for (int k = 0; k < 10; ++k) in.number("a direct ratio");
    std::vector<double> c;
    for (long k = 0; k < mc; ++k) {
        c.push_back(in.number("a C angle"));
        if (k > 0 && !(c.back() > c[c.size() - 2])) in.fail("C angles must increase");
    }
    for (long k = 0; k < ng; ++k) {
        p.v.push_back(in.number("a gamma angle"));
        if (k > 0 && !(p.v.back() > p.v[p.v.size() - 2])) in.fail("gamma angles must increase");
    }
    if (p.v.front() < 0 || p.v.back() > 180) in.fail("gamma angles lie within 0 to 180 degrees");
    const auto planes = stored_planes(isym, c, in);
    std::vector<double> h, values;
    const double scale = lamp_flux / 1000 * cfli;
    for (const auto plane : planes) {
        h.push_back(c[plane]);
        for (long k = 0; k < ng; ++k) {
            const double cd = in.number("an intensity (cd/klm) of C" + std::to_string(c[plane]));
            if (cd < 0) in.fail("a negative intensity (" + std::to_string(cd) + ")");
            values.push_back(photometry::checked_candela(cd, scale, in));
        }
    }
    if (!in.at_end()) {
        in.number("the end of the file");
        in.fail("numbers left over after the " + std::to_string(planes.size()) + " x " +
                std::to_string(ng) + " intensities Isym " + std::to_string(isym) + " stores");
    }
    const auto end = in.where();
    photometry::complete_type_c(p, h, values,
                                [&](const std::string& m) { throw InputError(end, m); });
    return p;
}

Photometry parse_photometry(std::string_view text, const std::string& name,
                            const IncludeReader& read_include) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char ch) { return char(std::tolower(ch)); });
    if (lower.ends_with(".ldt")) return parse_ldt(text, name);
    return parse_ies(text, name, read_include);
}

std::vector<std::string> flux_warnings(const Photometry& p, double tolerance) {
    std::vector<std::string> out;
    const double flux = p.flux();
    char line[400];
    if (p.stated_flux > 0 && std::abs(flux - p.stated_flux) > tolerance * p.stated_flux) {
        std::snprintf(line, sizeof line,
                      "%s: the intensities integrate to %.1f lm, but the file states %.1f lm "
                      "(lamps x LORL): %+.1f%%",
                      p.source.c_str(), flux, p.stated_flux,
                      100 * (flux - p.stated_flux) / p.stated_flux);
        out.push_back(line);
    }
    if (p.stated_flux == 0 && p.lamp_lumens > 0 && flux > (1 + tolerance) * p.lamp_lumens) {
        std::snprintf(line, sizeof line,
                      "%s: the intensities integrate to %.1f lm, more than its lamps' %.1f lm "
                      "(a light output ratio of %.1f%%)",
                      p.source.c_str(), flux, p.lamp_lumens, 100 * flux / p.lamp_lumens);
        out.push_back(line);
    }
    if (p.stated_downward_percent >= 0 && flux > 0) {
        const double down = 100 * p.downward_flux() / flux;
        if (std::abs(down - p.stated_downward_percent) > 100 * tolerance) {
            std::snprintf(line, sizeof line,
                          "%s: %.1f%% of the flux goes downward, but the file states a DFF of "
                          "%.1f%%",
                          p.source.c_str(), down, p.stated_downward_percent);
            out.push_back(line);
        }
    }
    return out;
}

} // namespace rad
