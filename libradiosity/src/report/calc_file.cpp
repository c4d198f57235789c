// The calculation-surfaces CSV: a header line naming the columns, then one surface or
// observer a line.
#include "photometry/text_lines.hpp"
#include "radiosity/calc_surfaces.hpp"

#include "radfmt/names.hpp"
#include "radiosity/text_input.hpp"

#include <map>
#include <set>

namespace rad {
namespace {

constexpr const char* kColumns =
    "name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing,border,Em,U0,Emin,UGRL,angle,DF,sDA,ASE";

const std::map<std::string, CalcKind>& kinds() {
    static const std::map<std::string, CalcKind> table{
        {"workplane", CalcKind::WorkPlane},
        {"task", CalcKind::Task},
        {"wall", CalcKind::Wall},
        {"ceiling", CalcKind::Ceiling},
        {"floor", CalcKind::Floor},
        {"observer", CalcKind::Observer},
        {"camera", CalcKind::Camera},
        {"escape-route", CalcKind::EscapeRoute},
        {"open-area", CalcKind::OpenArea},
        {"cylindrical", CalcKind::Cylindrical},
        {"semi-cylindrical", CalcKind::SemiCylindrical}};
    return table;
}

// One data line's fields by column name.
class CsvRow {
  public:
    CsvRow(FileLoc where, std::map<std::string, std::string> fields)
        : where_(std::move(where)), fields_(std::move(fields)) {}
    const FileLoc& where() const { return where_; }
    const std::string& text(const std::string& column) const {
        static const std::string none;
        const auto it = fields_.find(column);
        return it == fields_.end() ? none : it->second;
    }
    // The column's number; `fallback` when it is empty (NaN fallback and `required`: refused).
    double number(const std::string& column, double fallback, bool required = false) const {
        const auto& t = text(column);
        if (t.empty()) {
            if (required) throw InputError(where_, column + " is empty: give a number");
            return fallback;
        }
        double value = 0;
        if (!photometry::parse_number(t, value))
            throw InputError(where_, column + " is " + photometry::quoted(t) + ", not a number");
        return value;
    }
    Vec3 vector(const std::string& prefix, bool required) const {
        const double none = std::numeric_limits<double>::quiet_NaN();
        return {number(prefix + "x", none, required), number(prefix + "y", none, required),
                number(prefix + "z", none, required)};
    }
    double at_least_zero(const std::string& column, double fallback) const {
        const double value = number(column, fallback);
        if (value < 0) throw InputError(where_, column + " is negative: give 0 or more");
        return value;
    }

    // `columns` that `who` ("an observer") does not have must be empty.
    void refuse_any(std::initializer_list<const char*> columns, const std::string& who) const {
        for (const char* column : columns)
            if (!text(column).empty())
                throw InputError(where_, who + " has no " + column + ": leave it empty");
    }

  private:
    FileLoc where_;
    std::map<std::string, std::string> fields_;
};

std::map<std::string, std::size_t> header_columns(const std::vector<std::string>& header,
                                                  const FileLoc& where) {
    if (header.empty() || header[0] != "name")
        throw InputError(where, std::string("the first line names the columns, the first "
                                            "being 'name' (") +
                                    kColumns + ")");
    static const std::set<std::string> known{
        "name",    "kind",   "x",  "y",  "z",    "ux",   "uy",    "uz", "vx",  "vy", "vz",
        "spacing", "border", "Em", "U0", "Emin", "UGRL", "angle", "DF", "sDA", "ASE"};
    std::map<std::string, std::size_t> columns;
    for (std::size_t k = 0; k < header.size(); ++k) {
        if (!known.count(header[k]))
            throw InputError(where, "unknown column '" + header[k] + "' (" + kColumns + ")");
        if (!columns.emplace(header[k], k).second)
            throw InputError(where, "column '" + header[k] + "' is named twice");
    }
    for (const char* required : {"x", "y", "z", "ux", "uy", "uz"})
        if (!columns.count(required))
            throw InputError(where, std::string("the header line has no column '") + required +
                                        "' (" + kColumns + ")");
    return columns;
}

CalcSurface surface_of(const CsvRow& row, CalcKind kind) {
    CalcSurface s;
    s.name = row.text("name");
    s.where = row.where();
    s.kind = kind;
    s.corner = row.vector("", true);
    s.u = row.vector("u", true);
    s.v = row.vector("v", true);
    if (length(cross(s.u, s.v)) <= 1e-12 * dot(s.u, s.u) + 1e-300 || !(length(s.u) > 0))
        throw InputError(row.where(), "the edges u and v span no area (zero, or parallel): give "
                                      "two sides of the rectangle from its corner");
    s.spacing_m = row.at_least_zero("spacing", 0);
    s.border_m = row.at_least_zero("border", kNoRequirement);
    // EN 12464-1:2021 (5.2.2): in enclosed spaces walls get Em 50 lx and ceilings 30 lx at
    // least, with U0 0.10, unless the file says otherwise.
    const bool wall = kind == CalcKind::Wall, ceiling = kind == CalcKind::Ceiling;
    s.required.em = row.at_least_zero("Em", wall ? 50.0 : ceiling ? 30.0 : kNoRequirement);
    s.required.u0 = row.at_least_zero("U0", wall || ceiling ? 0.1 : kNoRequirement);
    // EN 1838: 1 lx on an escape route's centre line, 0.5 lx over an open area, Emax/Emin at
    // most 40 on both.
    const double emergency_minimum = kind == CalcKind::EscapeRoute ? 1.0 : 0.5;
    s.required.emin =
        row.at_least_zero("Emin", is_emergency(kind) ? emergency_minimum : kNoRequirement);
    if (is_emergency(kind)) s.required.max_over_min = 40;
    s.required.df = row.at_least_zero("DF", kNoRequirement);
    s.required.sda = row.at_least_zero("sDA", kNoRequirement);
    s.required.ase = row.at_least_zero("ASE", kNoRequirement);
    for (const char* share : {"sDA", "ASE"})
        if (row.number(share, 0) > 100)
            throw InputError(row.where(), std::string(share) + " is a share of the points in %, "
                                                               "at most 100");
    if (s.required.u0 > 1) throw InputError(row.where(), "U0 is Emin/Em, at most 1: give e.g. 0.6");
    for (const char* column : {"UGRL", "angle"})
        if (!row.text(column).empty())
            throw InputError(row.where(), std::string(column) +
                                              " is an observer's or a camera's: leave it empty "
                                              "on a surface's line");
    return s;
}

CalcObserver observer_of(const CsvRow& row) {
    CalcObserver o;
    o.name = row.text("name");
    o.where = row.where();
    o.position = row.vector("", true);
    const Vec3 view = row.vector("u", true);
    if (!(length(view) > 0))
        throw InputError(row.where(), "an observer's line of sight ux uy uz is zero: give the "
                                      "way the observer looks");
    o.view = normalized(view);
    o.ugr_limit = row.at_least_zero("UGRL", kNoRequirement);
    row.refuse_any(
        {"vx", "vy", "vz", "spacing", "border", "Em", "U0", "Emin", "angle", "DF", "sDA", "ASE"},
        "an observer");
    return o;
}

CalcCamera camera_of(const CsvRow& row) {
    CalcCamera c;
    c.name = row.text("name");
    c.where = row.where();
    c.position = row.vector("", true);
    const Vec3 direction = row.vector("u", true);
    if (!(length(direction) > 0))
        throw InputError(row.where(), "a camera's direction ux uy uz is zero: give the way it "
                                      "looks");
    c.direction = normalized(direction);
    const bool up_given =
        !row.text("vx").empty() || !row.text("vy").empty() || !row.text("vz").empty();
    if (up_given) c.up = row.vector("v", true);
    if (!(length(c.up) > 0) || length(cross(c.direction, c.up)) < 1e-6 * length(c.up))
        throw InputError(row.where(), "a camera's up vx vy vz is zero or along its direction: "
                                      "give another (empty: 0 1 0)");
    c.angle_deg = row.number("angle", 60);
    if (!(c.angle_deg > 0 && c.angle_deg < 180))
        throw InputError(row.where(), "angle is the camera's horizontal view in degrees, "
                                      "between 0 and 180 (empty: 60)");
    row.refuse_any({"spacing", "border", "Em", "U0", "Emin", "UGRL", "DF", "sDA", "ASE"},
                   "a camera");
    return c;
}

} // namespace

const char* calc_kind_name(CalcKind kind) {
    for (const auto& [name, k] : kinds())
        if (k == kind) return name.c_str();
    return "?";
}

std::string csv_field(const std::string& text) {
    const bool plain = text.find_first_of(",\"") == std::string::npos &&
                       (text.empty() || (text.front() != ' ' && text.front() != '\t' &&
                                         text.back() != ' ' && text.back() != '\t'));
    if (plain) return text;
    std::string out = "\"";
    for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

CalcFile read_calc_file(const std::string& path) {
    CalcFile file;
    LineReader in(path);
    file.name = in.name();
    std::map<std::string, std::size_t> columns;
    std::set<std::string> names;
    std::string line;
    while (in.next(line)) {
        const FileLoc where{file.name, in.line_number()};
        if (in.line_number() == 1) line = std::string(photometry::plain_text(line, file.name));
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        // A quoted field may hold line breaks: the row goes on over the next lines.
        for (std::string more; photometry::csv_quote_open(line); line += '\n' + more)
            if (!in.next(more)) photometry::unclosed_csv_quote(where);
        const auto fields = photometry::csv_fields(line);
        if (columns.empty()) {
            columns = header_columns(fields, where);
            continue;
        }
        if (fields.size() > columns.size())
            throw InputError(where, std::to_string(fields.size()) +
                                        " fields, but the header "
                                        "has " +
                                        std::to_string(columns.size()) + " columns");
        std::map<std::string, std::string> by_column;
        for (const auto& [column, index] : columns)
            if (index < fields.size()) by_column[column] = fields[index];
        const CsvRow row(where, std::move(by_column));
        if (row.text("name").empty()) throw InputError(where, "the name is empty: name it");
        // The name goes into pages declared UTF-8 and into CSV and text outputs.
        if (const auto why = radfmt::name_problem(row.text("name")); !why.empty())
            throw InputError(where, photometry::quoted(row.text("name")) + " is " + why +
                                        ": names are UTF-8 text of at most 200 bytes without "
                                        "control characters");
        if (!names.insert(row.text("name")).second)
            throw InputError(where, "'" + row.text("name") + "' is named twice: names are unique");
        const auto& kind_text = row.text("kind");
        const auto kind = kinds().find(kind_text.empty() ? "workplane" : kind_text);
        if (kind == kinds().end())
            throw InputError(where, "kind is " + photometry::quoted(kind_text) +
                                        ": workplane, task, wall, ceiling, floor, observer or "
                                        "camera");
        if (kind->second == CalcKind::Observer)
            file.observers.push_back(observer_of(row));
        else if (kind->second == CalcKind::Camera)
            file.cameras.push_back(camera_of(row));
        else
            file.surfaces.push_back(surface_of(row, kind->second));
    }
    if (columns.empty()) throw InputError(FileLoc{file.name, 0}, "empty: no header line");
    if (file.surfaces.empty() && file.observers.empty() && file.cameras.empty())
        throw InputError(FileLoc{file.name, 0}, "no surface, observer or camera: add a line");
    return file;
}

} // namespace rad
