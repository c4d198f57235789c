// The luminaire layout: a CSV of placed, aimed and turned photometric files, read with the
// files it names (inside the layout's folder), then built into luminaires.
#include "photometry/text_lines.hpp"
#include "radfmt/chain.hpp"
#include "radfmt/names.hpp"
#include "radiosity/luminaires.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <unordered_set>

namespace rad {
namespace fs = std::filesystem;

namespace {
constexpr std::size_t kMaxSourceBytes = std::size_t(64) << 20; // a photometric file is small

// A regular file's text, refused past kMaxSourceBytes (FileLoc names who asked for it).
std::string read_text(const fs::path& path, const FileLoc& asked) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw InputError(asked, path.string() + " does not exist");
    if (!S_ISREG(st.st_mode)) throw InputError(asked, path.string() + " is not a regular file");
    if (std::size_t(st.st_size) > kMaxSourceBytes)
        throw InputError(asked, path.string() + " is over 64 MiB: not a photometric file");
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    if (in.bad() || !in)
        if (!in.eof()) throw SystemError(path.string() + ": cannot read it");
    return s.str();
}

// `name` (relative to `folder`) as a path inside `root`, or InputError at `asked`.
std::string inside(const fs::path& root, const fs::path& folder, const std::string& name,
                   const FileLoc& asked) {
    const fs::path given(name);
    if (name.empty()) throw InputError(asked, "no file named");
    if (given.is_absolute())
        throw InputError(asked, "'" + name + "' is an absolute path: name files relative to " +
                                    "the layout's folder, inside it");
    const auto relative = (folder / given).lexically_normal();
    if (relative.empty() || *relative.begin() == "..")
        throw InputError(asked, "'" + name + "' leads out of the layout's folder " + root.string() +
                                    ": copy the file into it");
    std::error_code ec;
    const auto canonical_root = fs::weakly_canonical(root, ec);
    const auto canonical = fs::weakly_canonical(root / relative, ec);
    const auto rel = canonical.lexically_relative(canonical_root);
    if (ec || rel.empty() || *rel.begin() == "..")
        throw InputError(asked, "'" + name + "' leads out of the layout's folder (a link): " +
                                    "copy the file into it");
    return relative.generic_string();
}

// The column indices of the header line (InputError naming a missing one).
std::map<std::string, std::size_t> column_indices(const std::vector<std::string>& header,
                                                  const FileLoc& where) {
    std::map<std::string, std::size_t> columns;
    for (std::size_t k = 0; k < header.size(); ++k) columns[header[k]] = k;
    for (const char* required : {"name", "photometry", "x", "y", "z"})
        if (!columns.count(required))
            throw InputError(where, std::string("the header line has no column '") + required +
                                        "' (name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,"
                                        "maintenance,group)");
    for (const auto& [name, index] : columns)
        if (name != "name" && name != "photometry" && name != "x" && name != "y" && name != "z" &&
            name != "aim_x" && name != "aim_y" && name != "aim_z" && name != "spin" &&
            name != "maintenance" && name != "group" && name != "cct" && name != "emergency" &&
            name != "llmf" && name != "lsf" && name != "lmf" && name != "rsmf")
            throw InputError(where, "unknown column '" + name +
                                        "' (name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,"
                                        "maintenance,group,cct,emergency,llmf,lsf,lmf,rsmf)");
    return columns;
}

// The layout's rows: (line, fields), read by column name through the header's columns (shared
// by every row: a map a row took a million rows past 1.7 GB).
struct Row {
    int line = 0;
    std::vector<std::string> values;
    std::shared_ptr<const std::map<std::string, std::size_t>> columns;
    const std::string& operator[](const std::string& key) const {
        static const std::string none;
        const auto it = columns->find(key);
        return it == columns->end() || it->second >= values.size() ? none : values[it->second];
    }
};

std::vector<Row> layout_rows(const std::string& text, const std::string& name) {
    const auto lines = photometry::split_lines(photometry::plain_text(text, name));
    std::vector<Row> rows;
    std::shared_ptr<const std::map<std::string, std::size_t>> columns;
    bool header = true;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const FileLoc where{name, int(i + 1)};
        std::string line(lines[i]);
        if (line.find_first_not_of(" \t") == std::string_view::npos || line.starts_with('#'))
            continue;
        // A quoted field may hold line breaks: the row goes on over the next lines.
        while (photometry::csv_quote_open(line)) {
            if (++i == lines.size()) photometry::unclosed_csv_quote(where);
            line += '\n';
            line += lines[i];
        }
        auto fields = photometry::csv_fields(line);
        if (header) {
            columns = std::make_shared<const std::map<std::string, std::size_t>>(
                column_indices(fields, where));
            header = false;
            continue;
        }
        if (fields.size() > columns->size())
            throw InputError(where, std::to_string(fields.size()) + " fields, but the header has " +
                                        std::to_string(columns->size()) + " columns");
        rows.push_back(Row{where.line, std::move(fields), columns});
    }
    if (header) throw InputError(FileLoc{name, 0}, "empty layout: no header line");
    if (rows.empty()) throw InputError(FileLoc{name, 0}, "the layout places no luminaire");
    return rows;
}

double field_number(const Row& row, const std::string& column, double fallback,
                    const std::string& name) {
    const auto& text = row[column];
    if (text.empty()) return fallback;
    double value = 0;
    if (!photometry::parse_number(text, value))
        throw InputError(FileLoc{name, row.line},
                         column + " is " + photometry::quoted(text) + ", not a number");
    return value;
}

// The rotation taking unit `from` to unit `to` by the shortest arc, applied to `v`.
Vec3 rotate_shortest(const Vec3& from, const Vec3& to, const Vec3& v) {
    const double c = dot(from, to);
    Vec3 axis = cross(from, to);
    double s = length(axis);
    if (s < 1e-12) {
        if (c > 0) return v;
        // Opposite: 180 degrees about +X (the rule for straight up), or any perpendicular.
        axis = std::abs(from[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
        axis = normalized(axis - from * dot(axis, from));
        s = 0;
    } else {
        axis = axis * (1 / s);
    }
    // Rodrigues: v cos + (k x v) sin + k (k.v)(1 - cos).
    return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
}

// Orientation of a luminaire from its aim and spin (see build_luminaires).
void orient(Luminaire& l, Vec3 aim, double spin_deg) {
    const double a = spin_deg * std::numbers::pi / 180;
    // Spin about +Y (counter-clockwise seen from above): +X turns towards -Z.
    const Vec3 c0{std::cos(a), 0, -std::sin(a)};
    const Vec3 c90{-std::sin(a), 0, -std::cos(a)};
    const Vec3 down{0, -1, 0};
    aim = normalized(aim);
    l.nadir = aim;
    l.c0 = normalized(rotate_shortest(down, aim, c0));
    l.c90 = normalized(rotate_shortest(down, aim, c90));
}
} // namespace

Photometry read_photometry_file(const fs::path& path) {
    const auto text = read_text(path, FileLoc{path.string(), 0});
    const auto root = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    const IncludeReader include = [&](const std::string& name, const FileLoc& asked) {
        return read_text(root / inside(root, "", name, asked), asked);
    };
    return parse_photometry(text, path.string(), include);
}

LuminaireSources read_luminaire_sources(const fs::path& layout) {
    LuminaireSources sources;
    sources.layout_name = layout.string();
    sources.layout_text = read_text(layout, FileLoc{layout.string(), 0});
    const auto root = layout.parent_path().empty() ? fs::path(".") : layout.parent_path();
    std::map<std::string, bool> seen;
    std::set<std::string> named; // the photometry column's texts already read
    std::unordered_set<std::string> groups;
    for (const auto& row : layout_rows(sources.layout_text, sources.layout_name)) {
        const FileLoc where{sources.layout_name, row.line};
        groups.insert(row["group"].empty() ? row["name"] : row["group"]);
        // Each text once: its path is resolved on the file system (a million rows naming
        // one file took 20 s of path lookups).
        if (!named.insert(row["photometry"]).second) continue;
        const auto relative = inside(root, "", row["photometry"], where);
        if (seen[relative]) continue;
        seen[relative] = true;
        auto text = read_text(root / relative, where);
        // The TILT file an IES file names, relative to it.
        const auto folder = fs::path(relative).parent_path();
        const IncludeReader include = [&](const std::string& name, const FileLoc& asked) {
            const auto tilt = inside(root, folder, name, asked);
            auto tilt_text = read_text(root / tilt, asked);
            if (!seen[tilt]) sources.files.emplace_back(tilt, tilt_text);
            seen[tilt] = true;
            return tilt_text;
        };
        parse_photometry(text, relative, include); // refuses a bad file here, by its name
        sources.files.emplace_back(relative, std::move(text));
    }
    sources.group_count = groups.size();
    return sources;
}

namespace {
// The set's photometries by the layout's photometry column: each text resolved once (a path
// lookup a row made a million rows take 20 s), each file parsed once.
class PhotometryIndex {
  public:
    explicit PhotometryIndex(const LuminaireSources& sources)
        : text_of_(sources.files.begin(), sources.files.end()) {}
    // The index into set.photometries of the file `named` (parsed and added when new).
    std::size_t of(const std::string& named, const FileLoc& where, LuminaireSet& set) {
        auto path = relative_of_.find(named);
        if (path == relative_of_.end())
            path = relative_of_.emplace(named, inside(".", "", named, where)).first;
        const auto& relative = path->second;
        if (const auto known = index_of_.find(relative); known != index_of_.end())
            return known->second;
        const auto it = text_of_.find(relative);
        if (it == text_of_.end())
            throw InputError(where,
                             "the photometric file '" + relative + "' is not among the files");
        const auto folder = fs::path(relative).parent_path();
        const IncludeReader include = [&](const std::string& name, const FileLoc& asked) {
            const auto tilt = inside(".", folder, name, asked);
            const auto t = text_of_.find(tilt);
            if (t == text_of_.end())
                throw InputError(asked, "the TILT file '" + tilt + "' is missing");
            return t->second;
        };
        index_of_[relative] = set.photometries.size();
        set.photometries.push_back(parse_photometry(it->second, relative, include));
        set.photometry_flux.push_back(set.photometries.back().flux());
        for (auto& w : flux_warnings(set.photometries.back())) set.warnings.push_back(w);
        return set.photometries.size() - 1;
    }

  private:
    std::map<std::string, std::string> text_of_, relative_of_; // relative_of_: column text
    std::map<std::string, std::size_t> index_of_;              // by relative path
};
} // namespace

// The maintenance factor's parts (CIE 97: lamp lumen maintenance, lamp survival, luminaire
// and room surface maintenance), each 1 when empty: their product is the factor, and a
// maintenance column beside them must agree with it.
template <class Number>
void read_maintenance_parts(const Row& row, const FileLoc& where, const Number& number,
                            Luminaire& l) {
    constexpr std::array<const char*, 4> kParts{"llmf", "lsf", "lmf", "rsmf"};
    bool any = false;
    for (const char* part : kParts) any = any || !row[part].empty();
    if (!any) return;
    double product = 1;
    for (std::size_t k = 0; k < kParts.size(); ++k) {
        l.maintenance_parts[k] = number(kParts[k], 1);
        if (!(l.maintenance_parts[k] > 0 && l.maintenance_parts[k] <= 1))
            throw InputError(where, std::string(kParts[k]) + " must be in (0, 1]");
        product *= l.maintenance_parts[k];
    }
    if (!row["maintenance"].empty() && std::abs(l.maintenance - product) > 5e-4)
        throw InputError(where, "maintenance " + row["maintenance"] +
                                    " is not llmf x lsf x lmf x rsmf = " + std::to_string(product) +
                                    ": give the parts or the factor, or make them agree");
    l.maintenance = product;
    l.maintenance_parts_given = true;
}

LuminaireSet build_luminaires(const LuminaireSources& sources, double metres_per_unit) {
    LuminaireSet set;
    set.metres_per_unit = metres_per_unit;
    PhotometryIndex photometries(sources);
    std::map<std::string, int> names;
    std::map<std::string, std::size_t> group_index; // into set.groups
    for (const auto& row : layout_rows(sources.layout_text, sources.layout_name)) {
        const FileLoc where{sources.layout_name, row.line};
        Luminaire l;
        l.name = row["name"];
        l.line = row.line;
        if (l.name.empty()) throw InputError(where, "a luminaire needs a name");
        for (const auto* name : {&row["name"], &row["group"]})
            if (!name->empty())
                if (const auto why = radfmt::name_problem(*name); !why.empty())
                    throw InputError(where, photometry::quoted(*name) + " is " + why +
                                                ": names are UTF-8 text of at most 200 bytes "
                                                "without control characters");
        if (names.count(l.name))
            throw InputError(where, "the name '" + l.name + "' is used on line " +
                                        std::to_string(names[l.name]) + " too");
        names[l.name] = row.line;
        l.photometry = photometries.of(row["photometry"], where, set);
        const auto number = [&](const char* column, double fallback) {
            return field_number(row, column, fallback, sources.layout_name);
        };
        for (const char* column : {"x", "y", "z"})
            if (row[column].empty())
                throw InputError(where, std::string(column) +
                                            " is empty: every luminaire needs its x, y and z");
        l.position = {number("x", 0), number("y", 0), number("z", 0)};
        Vec3 aim{number("aim_x", 0), number("aim_y", -1), number("aim_z", 0)};
        // A direction: scaled by its largest component first, so that 1e200 squared does not
        // overflow to a length of infinity (and the aim to zero).
        const double largest = std::max({std::abs(aim[0]), std::abs(aim[1]), std::abs(aim[2])});
        if (!(largest > 0) || !std::isfinite(largest))
            throw InputError(where, "the aim is the zero vector");
        aim = aim * (1 / largest);
        orient(l, aim, number("spin", 0));
        l.maintenance = number("maintenance", 1);
        if (!(l.maintenance > 0 && l.maintenance <= 1))
            throw InputError(where, "maintenance must be in (0, 1]");
        read_maintenance_parts(row, where, number, l);
        l.emergency = number("emergency", 0);
        if (!(l.emergency >= 0 && l.emergency <= 1))
            throw InputError(where, "emergency is the share of the flux the luminaire gives on "
                                    "its battery (its emergency ballast lumen factor), 0 to 1 "
                                    "(empty or 0: not an emergency luminaire)");
        l.group = row["group"].empty() ? l.name : row["group"];
        const auto& p = set.photometries[l.photometry];
        // Tilt: the angle between the aim and straight down.
        const double tilt = std::acos(std::clamp(-l.nadir[1], -1.0, 1.0)) * 180 / std::numbers::pi;
        l.tilt_factor = p.tilt.factor(tilt);
        l.cct = number("cct", p.cct > 0 ? p.cct : 0);
        if (l.cct != 0 && !(l.cct >= 1667 && l.cct <= 25000))
            throw InputError(where, "cct " + row["cct"] + " K is outside 1667 to 25000 K");
        if (l.cct > 0) {
            const auto t = cct_tint(l.cct);
            l.tint = Rgb{{t[0], t[1], t[2]}};
        }
        // By a map: a layout may give every row a group of its own (a linear search made
        // 40,000 rows take 5 s).
        const auto [known, added] = group_index.try_emplace(l.group, set.groups.size());
        if (added) set.groups.push_back(l.group);
        l.group_index = known->second;
        set.luminaires.push_back(std::move(l));
    }
    return set;
}

double LuminaireSet::intensity(const Luminaire& l, const Vec3& d) const {
    const auto& p = photometries[l.photometry];
    const double f = dot(d, l.nadir), a = dot(d, l.c0), b = dot(d, l.c90);
    constexpr double kDeg = 180 / std::numbers::pi;
    double h = 0, v = 0;
    switch (p.type) {
    case PhotometricType::C:
        v = std::acos(std::clamp(f, -1.0, 1.0)) * kDeg;
        h = std::atan2(b, a) * kDeg;
        break;
    case PhotometricType::B:
        h = std::asin(std::clamp(b, -1.0, 1.0)) * kDeg;
        v = std::atan2(a, f) * kDeg;
        break;
    case PhotometricType::A:
        v = std::asin(std::clamp(a, -1.0, 1.0)) * kDeg;
        h = std::atan2(b, f) * kDeg;
        break;
    }
    return p.intensity(h, v) * l.maintenance * l.tilt_factor;
}

double LuminaireSet::flux(const Luminaire& l) const {
    return photometry_flux[l.photometry] * l.maintenance * l.tilt_factor;
}

double LuminaireSet::opening_size(const Luminaire& l) const {
    const auto& p = photometries[l.photometry];
    return std::max(p.length, p.width) / metres_per_unit;
}

std::size_t LuminaireSet::group_of(const Luminaire& l) const {
    return l.group_index;
}

double unit_metres(const std::string& unit) {
    if (unit == "m") return 1;
    if (unit == "cm") return 0.01;
    if (unit == "mm") return 0.001;
    if (unit == "ft") return 0.3048;
    if (unit == "in") return 0.0254;
    throw InputError("unknown unit '" + unit + "' (m, cm, mm, ft or in)");
}

double metres_per_unit(const radfmt::Header& mesh_header) {
    const auto* unit = mesh_header.find("unit");
    return unit ? unit_metres(*unit) : 1.0;
}

} // namespace rad

namespace rad {

std::optional<LuminaireSet>
solution_luminaires(const radfmt::Header& solution_header, const std::string& solution_path,
                    const std::string& path, const radfmt::MeshData& mesh,
                    const std::string& mesh_path, const radfmt::Header& mesh_header) {
    // A daylight solution's `direct` is its .sky: no luminaires.
    if (path.empty() && solution_header.find("sky_subdivision")) return std::nullopt;
    const auto lum_path = radfmt::solution_direct_path(solution_header, solution_path, path);
    if (lum_path.empty()) return std::nullopt;
    if (!fs::exists(lum_path))
        throw InputError(lum_path + ": the luminaires file the solution was solved with is not "
                                    "there (give its new place with --direct FILE)");
    radfmt::Header header;
    const auto lum = radfmt::read_luminaires(lum_path, &header);
    radfmt::require_same_geometry(lum_path, header, lum.patch_count, mesh_path, mesh,
                                  "run rad-ff --luminaires and rad-solve again");
    if (radfmt::solution_direct_changed(solution_header, header.file_hash))
        throw InputError(lum_path + " is not the luminaires file the solution was solved "
                                    "with (it changed since): run rad-solve --direct again");
    auto set = build_luminaires({lum.layout_name, lum.layout_text, lum.files},
                                metres_per_unit(mesh_header));
    const auto* count = header.find("luminaires");
    check_luminaires_file(set, lum.groups, count ? std::atol(count->c_str()) : -1, lum_path);
    return set;
}

void check_luminaires_file(const LuminaireSet& set, const std::vector<std::string>& groups,
                           long recorded_count, const std::string& path) {
    const auto join = [](const std::vector<std::string>& names) {
        std::string out;
        for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
        return out;
    };
    const std::string advice = ": the file contradicts itself (edited?); make it again with "
                               "rad-ff --luminaires";
    if (groups != set.groups)
        throw InputError(path + ": its light groups (" + join(groups) +
                         ") are not those its "
                         "layout makes (" +
                         join(set.groups) + ")" + advice);
    if (recorded_count >= 0 && std::size_t(recorded_count) != set.luminaires.size())
        throw InputError(path + ": its header records " + std::to_string(recorded_count) +
                         " luminaires, its layout places " + std::to_string(set.luminaires.size()) +
                         advice);
}

} // namespace rad
