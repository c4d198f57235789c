#include "radfmt/kinds.hpp"
#include "radfmt/names.hpp"

#include "body_checks.hpp"
#include "compact_rows.hpp"
#include "kind_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ostream>

namespace radfmt {
namespace fs = std::filesystem;

double MeshData::total_area() const {
    double sum = 0;
    for (const auto& p : patches) sum += p.area;
    return sum;
}

std::string MeshData::geometry_hash() const {
    BodyWriter w;
    w.u64(vertices.size());
    w.array(vertices);
    w.u64(patches.size());
    for (const auto& p : patches) w.array(std::span<const std::uint32_t>(p.corners));
    // Only a mesh with polygons hashes their corners: a mesh without keeps its hash.
    if (!polygon_corners.empty()) w.array(polygon_corners);
    // Only a mesh with mirrors or glass hashes each patch's specular part (not the material's
    // index: renaming or reordering materials changes no path of light).
    if (has_specular())
        for (const auto& p : patches) {
            const auto& s = materials[p.material].specular;
            w.u64(static_cast<std::uint64_t>(s.kind));
            if (!s.any()) continue;
            w.array(std::span<const double>(s.reflectance.c));
            w.array(std::span<const double>(s.transmittance.c));
            w.array(std::span<const double>(&s.ior, 1));
        }
    return "xxh64:" + hash_hex(w.hash());
}

std::vector<std::uint32_t> MeshData::specular_materials() const {
    std::vector<bool> used(materials.size(), false);
    for (const auto& p : patches)
        if (p.material < used.size()) used[p.material] = true;
    std::vector<std::uint32_t> out;
    for (std::uint32_t m = 0; m < materials.size(); ++m)
        if (used[m] && materials[m].specular.any()) out.push_back(m);
    return out;
}

bool MeshData::has_specular() const {
    return !specular_materials().empty();
}

const char* specular_kind_name(SpecularKind kind) {
    switch (kind) {
    case SpecularKind::mirror:
        return "mirror";
    case SpecularKind::fresnel:
        return "fresnel";
    case SpecularKind::pane:
        return "pane";
    case SpecularKind::dielectric:
        return "dielectric";
    case SpecularKind::none:
        break;
    }
    return "none";
}

void MeshData::set_corners(Patch& patch, std::span<const std::uint32_t> list, bool as_polygon) {
    if (list.size() < 3) throw std::logic_error("a patch needs 3 corners or more");
    if (!as_polygon && list.size() <= 4) {
        patch.corners = {kNoVertex, kNoVertex, kNoVertex, kNoVertex};
        std::copy(list.begin(), list.end(), patch.corners.begin());
        return;
    }
    patch.corners = {static_cast<std::uint32_t>(polygon_corners.size()),
                     static_cast<std::uint32_t>(list.size()), kNoVertex, kPolygon};
    polygon_corners.insert(polygon_corners.end(), list.begin(), list.end());
}

std::size_t MeshData::polygon_count() const {
    return static_cast<std::size_t>(std::count_if(patches.begin(), patches.end(),
                                                  [](const Patch& p) { return p.is_polygon(); }));
}

namespace {
bool finite(const Vec3& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}
} // namespace

std::vector<std::string> detail::read_group_names(BodyReader& r, std::uint64_t count) {
    std::vector<std::string> names;
    for (std::uint64_t g = 0; g < count; ++g) {
        names.push_back(r.string());
        if (const auto why = name_problem(names.back()); !why.empty())
            r.fail("light group " + std::to_string(g) + " has " + why);
    }
    return names;
}

void detail::write_group_rows(std::ostream& out, const std::vector<std::string>& groups,
                              std::span<const Rgb> values) {
    char line[160];
    const std::size_t n = groups.empty() ? 0 : values.size() / groups.size();
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t g = 0; g < groups.size(); ++g) {
            const auto& v = values[i * groups.size() + g];
            std::snprintf(line, sizeof line, "%zu,", i);
            out << line << groups[g];
            std::snprintf(line, sizeof line, ",%.10g,%.10g,%.10g\n", v[0], v[1], v[2]);
            out << line;
        }
        if (!out) return;
    }
}

void detail::require_count(const Header& header, const char* key, std::uint64_t count,
                           BodyReader& r) {
    const auto* value = header.find(key);
    if (value && *value != std::to_string(count))
        r.fail(std::string("the header says ") + key + "=" + *value + " but the body holds " +
               std::to_string(count));
}
using detail::require_count;

static std::string number(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

// ---- mesh ----

namespace {
// A triangle or quad refers to vertices; a polygon to a run of at least 4 of the polygon
// corners (fewer would be a triangle).
void check_patch_corners(const Patch& p, std::size_t i, std::uint64_t vertices,
                         std::uint64_t polygon_corners, BodyReader& r) {
    if (p.is_polygon()) {
        if (p.corners[1] < 4 || p.corners[2] != kNoVertex ||
            std::uint64_t(p.corners[0]) + p.corners[1] > polygon_corners)
            r.fail("patch " + std::to_string(i) + " is a polygon of corners " +
                   std::to_string(p.corners[0]) + " to " +
                   std::to_string(std::uint64_t(p.corners[0]) + p.corners[1]) + " of " +
                   std::to_string(polygon_corners) + " (a polygon has 4 corners or more)");
        return;
    }
    for (int k = 0; k < 4; ++k)
        if (p.corners[k] >= vertices && !(k == 3 && p.corners[k] == kNoVertex))
            r.fail("patch " + std::to_string(i) + " refers to vertex " +
                   std::to_string(p.corners[k]) + " of " + std::to_string(vertices));
}
// Every polygon's fan from corner 0 must cover it: no fan triangle wound against the patch
// (beyond rounding: a millionth of the patch's area), so consumers may split it so.
void check_polygon_fans(const MeshData& mesh, BodyReader& r) {
    auto minus = [](const Vec3& a, const Vec3& b) {
        return Vec3{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    };
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& p = mesh.patches[i];
        if (!p.is_polygon()) continue;
        const auto corners = mesh.corners(p);
        const Vec3& o = mesh.vertices[corners[0]];
        for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
            const Vec3 a = minus(mesh.vertices[corners[k]], o);
            const Vec3 b = minus(mesh.vertices[corners[k + 1]], o);
            const double signed_area = 0.5 * (p.normal[0] * (a[1] * b[2] - a[2] * b[1]) +
                                              p.normal[1] * (a[2] * b[0] - a[0] * b[2]) +
                                              p.normal[2] * (a[0] * b[1] - a[1] * b[0]));
            if (signed_area < -1e-6 * p.area)
                r.fail("polygon patch " + std::to_string(i) +
                       " is not star-shaped from its first corner (fan triangle " +
                       std::to_string(k - 1) + " is wound backwards)");
        }
    }
}
// A patch's stored area must be what its corners enclose, within a thousandth: a body can
// pass its checksum and still say a patch is a million times its size, or be a polygon whose
// corners are one point. What they enclose is the vector area (half the length of the sum of
// its fan's cross products, Newell's, which the mesher stores): a warped quad's triangles add
// up to more (1% for a corner 0.2 off its plane) and were refused though rad-mesh wrote them.
// Taken from corner 0, so far from the origin the differences keep their digits.
void check_patch_areas(const MeshData& mesh, BodyReader& r) {
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& p = mesh.patches[i];
        const auto corners = mesh.corners(p);
        const Vec3& o = mesh.vertices[corners[0]];
        double c[3] = {0, 0, 0};
        for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
            const Vec3& a = mesh.vertices[corners[k]];
            const Vec3& b = mesh.vertices[corners[k + 1]];
            const double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
            const double v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
            c[0] += u[1] * v[2] - u[2] * v[1];
            c[1] += u[2] * v[0] - u[0] * v[2];
            c[2] += u[0] * v[1] - u[1] * v[0];
        }
        const double area = 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (!(std::abs(area - p.area) <= 1e-3 * std::max(area, p.area)))
            r.fail("patch " + std::to_string(i) + " stores an area of " + number(p.area) +
                   ", but its corners enclose " + number(area));
    }
}
} // namespace

namespace {
// A material's specular part (mesh version 3), checked: a known kind, shares in [0, 1], an
// index of refraction in [1, 10].
Specular read_specular(BodyReader& r, const std::string& material) {
    Specular s;
    const auto kind = r.u64();
    const auto rho = r.array<double>(3, "specular reflectance");
    const auto tau = r.array<double>(3, "specular transmittance");
    const auto numbers = r.array<double>(2, "index of refraction and roughness");
    const auto in_unit = [](double x) { return x >= 0 && x <= 1; };
    bool sane = kind < kSpecularKinds && numbers[0] >= 1 && numbers[0] <= 10 && in_unit(numbers[1]);
    for (int k = 0; k < 3; ++k) {
        s.reflectance[k] = rho[k];
        s.transmittance[k] = tau[k];
        sane = sane && in_unit(rho[k]) && in_unit(tau[k]);
    }
    if (!sane)
        r.fail("material '" + material +
               "' has a specular part out of range (kind, shares in [0, 1], index in [1, 10])");
    s.kind = static_cast<SpecularKind>(kind);
    s.ior = numbers[0];
    s.roughness = numbers[1];
    return s;
}
} // namespace

void write_mesh(const fs::path& path, Header header, const MeshData& mesh) {
    header.kind = Kind::Mesh;
    header.set("patches", std::to_string(mesh.patches.size()));
    header.set("vertices", std::to_string(mesh.vertices.size()));
    header.set("groups", std::to_string(mesh.groups.size()));
    header.set("materials", std::to_string(mesh.materials.size()));
    header.set("total_area", number(mesh.total_area()));
    header.set("geometry_hash", mesh.geometry_hash());
    // Version 2 adds the polygons' corners; a mesh without polygons is written as version 1,
    // byte for byte what it was before polygons existed.
    const bool polygons = !mesh.polygon_corners.empty();
    // Version 3 adds the materials' specular parts, written only when a material has one.
    const bool specular = std::any_of(mesh.materials.begin(), mesh.materials.end(),
                                      [](const Material& m) { return m.specular.any(); });
    header.version = specular ? 3 : polygons ? 2 : 1;
    if (polygons) header.set("polygons", std::to_string(mesh.polygon_count()));

    const auto n = mesh.patches.size();
    std::vector<std::uint32_t> corners(4 * n), group(n), material(n);
    std::vector<double> area(n), centroid(3 * n), normal(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& p = mesh.patches[i];
        for (int k = 0; k < 4; ++k) corners[4 * i + k] = p.corners[k];
        group[i] = p.group;
        material[i] = p.material;
        area[i] = p.area;
        for (int k = 0; k < 3; ++k) {
            centroid[3 * i + k] = p.centroid[k];
            normal[3 * i + k] = p.normal[k];
        }
    }
    BodyWriter w;
    w.u64(mesh.vertices.size());
    w.array(mesh.vertices);
    w.u64(n);
    w.array(corners);
    w.array(group);
    w.array(material);
    w.array(area);
    w.array(centroid);
    w.array(normal);
    if (polygons || specular) {
        w.u64(mesh.polygon_corners.size());
        w.array(mesh.polygon_corners);
    }
    w.u64(mesh.groups.size());
    for (const auto& g : mesh.groups) w.string(g);
    w.u64(mesh.materials.size());
    // The writer keeps pointers to what it is given until the file is written.
    std::vector<std::array<double, 2>> numbers;
    numbers.reserve(mesh.materials.size());
    for (const auto& m : mesh.materials) {
        w.string(m.name);
        w.array(std::span<const double>(m.reflectance.c));
        w.array(std::span<const double>(m.emission.c));
        if (!specular) continue;
        const auto& s = m.specular;
        w.u64(static_cast<std::uint64_t>(s.kind));
        w.array(std::span<const double>(s.reflectance.c));
        w.array(std::span<const double>(s.transmittance.c));
        numbers.push_back({s.ior, s.roughness});
        w.array(std::span<const double>(numbers.back()));
    }
    write_file(path, std::move(header), w);
}

MeshData read_mesh(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Mesh;
    BodyReader r(path, &kind);
    MeshData mesh;
    const auto nv = r.count(24, "vertices");
    mesh.vertices = r.array<Vec3>(nv, "vertices");
    const auto n = r.count(4 * 4 + 4 + 4 + 8 + 24 + 24, "patches");
    const auto corners = r.array<std::uint32_t>(4 * n, "patch corners");
    const auto group = r.array<std::uint32_t>(n, "patch groups");
    const auto material = r.array<std::uint32_t>(n, "patch materials");
    const auto area = r.array<double>(n, "patch areas");
    const auto centroid = r.array<double>(3 * n, "patch centroids");
    const auto normal = r.array<double>(3 * n, "patch normals");
    if (r.header().version >= 2) {
        const auto nc = r.count(4, "polygon corners");
        mesh.polygon_corners = r.array<std::uint32_t>(nc, "polygon corners");
    }
    const auto ng = r.count(8, "groups");
    for (std::uint64_t i = 0; i < ng; ++i) mesh.groups.push_back(r.string());
    const bool specular = r.header().version >= 3;
    const auto nm = r.count(8 + 48 + (specular ? 72 : 0), "materials");
    for (std::uint64_t i = 0; i < nm; ++i) {
        Material m;
        m.name = r.string();
        const auto rho = r.array<double>(3, "reflectance");
        const auto e = r.array<double>(3, "emission");
        for (int k = 0; k < 3; ++k) {
            m.reflectance[k] = rho[k];
            m.emission[k] = e[k];
        }
        if (specular) m.specular = read_specular(r, m.name);
        mesh.materials.push_back(std::move(m));
    }
    r.expect_end();
    // Values a checksum cannot vouch for: a file can be valid and still hold nonsense.
    require_count(r.header(), "patches", n, r);
    require_count(r.header(), "vertices", nv, r);
    for (std::uint64_t v = 0; v < nv; ++v)
        if (!finite(mesh.vertices[v]))
            r.fail("vertex " + std::to_string(v) + " is not a finite point");
    for (std::size_t g = 0; g < mesh.groups.size(); ++g)
        if (const auto why = name_problem(mesh.groups[g]); !why.empty())
            r.fail("group " + std::to_string(g) + " has " + why +
                   " (rad-mesh makes names UTF-8 text: mesh the scene again)");
    for (std::size_t k = 0; k < mesh.materials.size(); ++k)
        if (const auto why = name_problem(mesh.materials[k].name); !why.empty())
            r.fail("material " + std::to_string(k) + " has " + why +
                   " (rad-mesh makes names UTF-8 text: mesh the scene again)");
    for (auto& m : mesh.materials)
        for (int k = 0; k < 3; ++k)
            if (!(m.reflectance[k] >= 0 && std::isfinite(m.reflectance[k]) && m.emission[k] >= 0 &&
                  std::isfinite(m.emission[k])))
                r.fail("material '" + m.name +
                       "' has a negative or non-finite reflectance or emission");
    for (std::size_t c = 0; c < mesh.polygon_corners.size(); ++c)
        if (mesh.polygon_corners[c] >= nv)
            r.fail("polygon corner " + std::to_string(c) + " refers to vertex " +
                   std::to_string(mesh.polygon_corners[c]) + " of " + std::to_string(nv));
    mesh.patches.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        auto& p = mesh.patches[i];
        for (int k = 0; k < 4; ++k) p.corners[k] = corners[4 * i + k];
        check_patch_corners(p, i, nv, mesh.polygon_corners.size(), r);
        p.group = group[i];
        p.material = material[i];
        if (p.group >= ng || p.material >= nm)
            r.fail("patch " + std::to_string(i) + " refers to a missing group or material");
        p.area = area[i];
        for (int k = 0; k < 3; ++k) {
            p.centroid[k] = centroid[3 * i + k];
            p.normal[k] = normal[3 * i + k];
        }
        const double norm2 =
            p.normal[0] * p.normal[0] + p.normal[1] * p.normal[1] + p.normal[2] * p.normal[2];
        if (!(p.area > 0 && std::isfinite(p.area)) || !finite(p.centroid) ||
            !(std::abs(norm2 - 1) < 1e-6))
            r.fail("patch " + std::to_string(i) +
                   " has a non-positive area, a non-finite centroid or a normal that is not "
                   "unit length");
    }
    check_polygon_fans(mesh, r);
    check_patch_areas(mesh, r);
    if (header_out) *header_out = r.take_header();
    return mesh;
}

// ---- form factors ----

namespace {
void write_form_factor_body(const fs::path& path, Header header, const FormFactorData& ff,
                            Kind kind) {
    header.kind = kind;
    header.set("patches", std::to_string(ff.patch_count));
    header.set("nonzeros", std::to_string(ff.nonzeros()));
    if (ff.back_fraction.size() != ff.patch_count)
        throw std::logic_error("form factors written without one back-face fraction per row");
    if (ff.is_compact()) throw std::logic_error("form factors written from their compact rows");
    BodyWriter w;
    w.u64(ff.patch_count);
    w.u64(ff.nonzeros());
    // Version 3 of formfactors: compact rows (parts keep the plain arrays).
    std::vector<std::uint64_t> row_offset;
    std::vector<std::uint8_t> code;
    if (kind == Kind::FormFactors) {
        const auto denominator = compact::hit_denominator(header);
        w.u64(denominator);
        w.array(ff.row_start);
        row_offset.reserve(ff.patch_count + 1);
        for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
            row_offset.push_back(code.size());
            const auto b = ff.row_start[i], n = ff.row_start[i + 1] - b;
            compact::encode_row({ff.columns.data() + b, n}, {ff.values.data() + b, n}, denominator,
                                code);
        }
        row_offset.push_back(code.size());
        w.array(row_offset);
        w.array(code);
    } else {
        w.array(ff.row_start);
        w.array(ff.columns);
        w.array(ff.values);
    }
    w.array(ff.back_fraction);
    write_file(path, std::move(header), w);
}

// Version 3's row offsets, checked against the row starts.
std::vector<std::uint64_t> read_row_offsets(BodyReader& r, const FormFactorData& ff,
                                            std::uint64_t nnz) {
    auto row_offset = r.array<std::uint64_t>(ff.patch_count + 1, "row offsets");
    if (ff.row_start.front() != 0 || ff.row_start.back() != nnz)
        r.fail("row starts do not span the non-zeros");
    if (row_offset.front() != 0) r.fail("row offsets do not start at 0");
    for (std::uint64_t i = 0; i < ff.patch_count; ++i)
        if (ff.row_start[i] > ff.row_start[i + 1] || row_offset[i] > row_offset[i + 1])
            r.fail("row starts or offsets decrease at row " + std::to_string(i));
    return row_offset;
}

// Where read_compact_rows puts each decoded row: into the plain arrays, or packed (then
// decoded into a scratch row first).
class DecodedRows {
  public:
    DecodedRows(FormFactorData& ff, std::uint64_t nnz, std::uint64_t denominator, bool packed)
        : ff_(ff), packed_(packed) {
        if (!packed_) {
            ff_.columns.resize(nnz);
            ff_.values.resize(nnz);
            return;
        }
        auto& rows = ff_.compact;
        rows.denominator = denominator;
        rows.value_of_count = compact::packed_value_table(denominator);
        rows.step.reserve(nnz);
        rows.count.reserve(nnz);
        rows.far_start = {0};
        rows.other_start = {0};
    }
    std::uint32_t* columns(std::uint64_t i) {
        return packed_ ? fit(scratch_columns_, i) : ff_.columns.data() + ff_.row_start[i];
    }
    float* values(std::uint64_t i) {
        return packed_ ? fit(scratch_values_, i) : ff_.values.data() + ff_.row_start[i];
    }
    void done(std::uint64_t i) {
        if (!packed_) return;
        auto& rows = ff_.compact;
        compact::pack_row(scratch_columns_.data(), scratch_values_.data(), ff_.row_size(i), rows);
        rows.far_start.push_back(rows.far_column.size());
        rows.other_start.push_back(rows.other_value.size());
    }

  private:
    // The scratch row, long enough for row i.
    template <class T> T* fit(std::vector<T>& scratch, std::uint64_t i) {
        if (scratch.size() < ff_.row_size(i)) scratch.resize(ff_.row_size(i));
        return scratch.data();
    }
    FormFactorData& ff_;
    bool packed_;
    std::vector<std::uint32_t> scratch_columns_;
    std::vector<float> scratch_values_;
};

// Version 3's rows: offsets checked, then the codes read in pieces and decoded into the
// arrays or packed (never the whole code and the rows at once).
void read_compact_rows(BodyReader& r, FormFactorData& ff, std::uint64_t nnz,
                       std::uint64_t denominator, bool packed) {
    const auto row_offset = read_row_offsets(r, ff, nnz);
    const std::uint64_t code_size = row_offset.back();
    r.begin_pieces(code_size, "row codes");
    DecodedRows rows(ff, nnz, denominator, packed);
    std::vector<std::uint8_t> buffer;
    std::size_t begin = 0, have = 0; // valid bytes: buffer[begin, begin + have)
    std::uint64_t left = code_size;
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        const auto length = static_cast<std::size_t>(row_offset[i + 1] - row_offset[i]);
        if (have < length) {
            if (have > 0) std::memmove(buffer.data(), buffer.data() + begin, have);
            begin = 0;
            const std::size_t capacity = std::max<std::size_t>(length, std::size_t(1) << 20);
            if (buffer.size() < capacity) buffer.resize(capacity);
            const auto more =
                static_cast<std::size_t>(std::min<std::uint64_t>(capacity - have, left));
            r.read_piece(buffer.data() + have, more);
            have += more;
            left -= more;
        }
        const auto b = ff.row_start[i];
        const std::string why =
            compact::decode_row(buffer.data() + begin, length, ff.row_start[i + 1] - b,
                                ff.patch_count, denominator, rows.columns(i), rows.values(i), i, b);
        if (!why.empty()) r.fail(why);
        rows.done(i);
        begin += length;
        have -= length;
    }
    r.end_pieces();
}

// The same bytes from a spool (FormFactorSpool::fill_body lays out the body as above).
void write_form_factor_body(const fs::path& path, Header header, FormFactorSpool& ff, Kind kind) {
    header.kind = kind;
    header.set("patches", std::to_string(ff.patch_count()));
    header.set("nonzeros", std::to_string(ff.nonzeros()));
    BodyWriter w;
    if (kind == Kind::FormFactors)
        ff.fill_compact_body(w, compact::hit_denominator(header));
    else
        ff.fill_body(w);
    write_file(path, std::move(header), w);
}

FormFactorData read_form_factor_body(const fs::path& path, Header* header_out, Kind kind,
                                     std::uint64_t* rows_begin = nullptr,
                                     std::uint64_t* rows_end = nullptr,
                                     FormFactorLayout layout = FormFactorLayout::plain) {
    BodyReader r(path, &kind);
    FormFactorData ff;
    ff.patch_count = r.count(8, "rows");
    const bool compact = kind == Kind::FormFactors && r.header().version >= 3;
    // A compact non-zero takes at least two bytes (column delta and count).
    const auto nnz = r.count(compact ? 2 : 8, "non-zeros");
    const std::uint64_t denominator = compact ? r.u64() : 0;
    ff.row_start = r.array<std::uint64_t>(ff.patch_count + 1, "row starts");
    if (compact) {
        // Packed only where the values are hit counts: other rows would not get smaller.
        const bool packed = layout == FormFactorLayout::compact && denominator > 0;
        read_compact_rows(r, ff, nnz, denominator, packed);
    } else {
        ff.columns = r.array<std::uint32_t>(nnz, "columns");
        ff.values = r.array<float>(nnz, "values");
    }
    // Parts have them from their version 1 on.
    if (r.header().version >= 2 || kind == Kind::FormFactorPart) {
        ff.back_fraction = r.array<float>(ff.patch_count, "back-face fractions");
        for (std::uint64_t i = 0; i < ff.patch_count; ++i)
            if (!(ff.back_fraction[i] >= 0 && ff.back_fraction[i] <= 1))
                r.fail("back-face fraction of row " + std::to_string(i) + " is not in [0, 1]");
    }
    r.expect_end();
    if (ff.row_start.front() != 0 || ff.row_start.back() != nnz)
        r.fail("row starts do not span the non-zeros");
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        if (ff.row_start[i] > ff.row_start[i + 1])
            r.fail("row starts decrease at row " + std::to_string(i));
    }
    for (auto c : ff.columns)
        if (c >= ff.patch_count) r.fail("column " + std::to_string(c) + " out of range");
    // A form factor is a fraction of what leaves a patch: finite, in [0, 1] (a little over
    // for estimator noise).
    for (std::uint64_t k = 0; k < ff.values.size(); ++k)
        if (!(ff.values[k] >= 0 && ff.values[k] <= 1.5f))
            r.fail("form factor " + std::to_string(k) + " (" + std::to_string(ff.values[k]) +
                   ") is not in [0, 1]");
    require_count(r.header(), "patches", ff.patch_count, r);
    require_count(r.header(), "nonzeros", nnz, r);
    if (kind == Kind::FormFactorPart) {
        // Its rows, [rows_begin, rows_end): within the matrix, and the only ones filled.
        std::uint64_t begin = 0, end = 0;
        try {
            begin = std::stoull(r.header().get("rows_begin", path.string()));
            end = std::stoull(r.header().get("rows_end", path.string()));
        } catch (const FormatError&) {
            throw;
        } catch (...) {
            r.fail("rows_begin or rows_end is not a row number");
        }
        if (!(begin < end && end <= ff.patch_count))
            r.fail("its rows " + std::to_string(begin) + ".." + std::to_string(end) +
                   " are not a range of the " + std::to_string(ff.patch_count) + " rows");
        for (std::uint64_t i = 0; i < ff.patch_count; ++i)
            if ((i < begin || i >= end) && ff.row_start[i] != ff.row_start[i + 1])
                r.fail("row " + std::to_string(i) + " is filled but outside its rows");
        if (rows_begin) *rows_begin = begin;
        if (rows_end) *rows_end = end;
    }
    if (header_out) *header_out = r.take_header();
    return ff;
}
} // namespace

std::uint64_t formfactors_hit_denominator(const Header& header) {
    return compact::hit_denominator(header);
}

void write_form_factors(const fs::path& path, Header header, const FormFactorData& ff) {
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactors);
}
FormFactorData read_form_factors(const fs::path& path, Header* header_out,
                                 FormFactorLayout layout) {
    return read_form_factor_body(path, header_out, Kind::FormFactors, nullptr, nullptr, layout);
}

void write_form_factor_part(const fs::path& path, Header header, const FormFactorData& ff,
                            std::uint64_t rows_begin, std::uint64_t rows_end) {
    header.set("rows_begin", std::to_string(rows_begin));
    header.set("rows_end", std::to_string(rows_end));
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactorPart);
}
void write_form_factors(const fs::path& path, Header header, FormFactorSpool& ff) {
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactors);
}
void write_form_factor_part(const fs::path& path, Header header, FormFactorSpool& ff,
                            std::uint64_t rows_begin, std::uint64_t rows_end) {
    header.set("rows_begin", std::to_string(rows_begin));
    header.set("rows_end", std::to_string(rows_end));
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactorPart);
}
FormFactorData read_form_factor_part(const fs::path& path, Header* header_out,
                                     std::uint64_t* rows_begin, std::uint64_t* rows_end) {
    return read_form_factor_body(path, header_out, Kind::FormFactorPart, rows_begin, rows_end);
}

// ---- radiosity ----

void write_radiosity(const fs::path& path, Header header, const RadiosityData& rad) {
    header.kind = Kind::Radiosity;
    header.set("patches", std::to_string(rad.radiosity.size()));
    if (rad.group_radiosity.size() != rad.radiosity.size() * rad.group_names.size())
        throw std::logic_error("radiosity written with a group array of the wrong size");
    if (!rad.group_names.empty()) {
        std::string names;
        for (const auto& g : rad.group_names) names += (names.empty() ? "" : ",") + g;
        header.set("light_groups", names);
    }
    BodyWriter w;
    w.u64(rad.radiosity.size());
    w.array(rad.radiosity);
    w.u64(rad.group_names.size());
    for (const auto& g : rad.group_names) w.string(g);
    w.array(rad.group_radiosity);
    write_file(path, std::move(header), w);
}

RadiosityData read_radiosity(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Radiosity;
    BodyReader r(path, &kind);
    RadiosityData rad;
    const auto n = r.count(24, "patches");
    rad.radiosity = r.array<Rgb>(n, "radiosity");
    if (r.header().version >= 2) {
        const auto groups = r.count(8, "light groups");
        rad.group_names = detail::read_group_names(r, groups);
        if (groups > 0 && n > (std::uint64_t(1) << 40) / groups)
            r.fail("too many light groups for the patches");
        rad.group_radiosity = r.array<Rgb>(n * groups, "light group radiosity");
    }
    r.expect_end();
    require_count(r.header(), "patches", n, r);
    for (const auto* values : {&rad.radiosity, &rad.group_radiosity})
        for (std::size_t i = 0; i < values->size(); ++i)
            for (int c = 0; c < 3; ++c)
                if (!((*values)[i][c] >= 0 && std::isfinite((*values)[i][c])))
                    r.fail("radiosity value " + std::to_string(i) + " is negative or not finite");
    if (header_out) *header_out = r.take_header();
    return rad;
}

// ---- CSV and summaries, one pair per kind ----

namespace {

void mesh_csv(const fs::path& path, std::ostream& out) {
    const auto mesh = read_mesh(path);
    char line[512];
    out << kind_info(Kind::Mesh).csv_columns << '\n';
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& p = mesh.patches[i];
        const auto& m = mesh.materials[p.material];
        std::snprintf(line, sizeof line,
                      "%zu,%s,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%."
                      "10g,%.10g,%.10g,%d\n",
                      i, mesh.groups[p.group].c_str(), m.name.c_str(), p.area, p.centroid[0],
                      p.centroid[1], p.centroid[2], p.normal[0], p.normal[1], p.normal[2],
                      m.reflectance[0], m.reflectance[1], m.reflectance[2], m.emission[0],
                      m.emission[1], m.emission[2], p.corner_count());
        out << line;
        if (!out) return; // the reader went away (closed pipe): stop writing
    }
}

std::string mesh_summary(const fs::path& path, Header& header) {
    const auto mesh = read_mesh(path, &header);
    std::size_t quads = 0, polygons = 0;
    for (const auto& p : mesh.patches) {
        polygons += p.is_polygon();
        quads += !p.is_polygon() && p.corner_count() == 4;
    }
    const std::string with_polygons =
        polygons ? std::to_string(polygons) + " polygons, " : std::string();
    std::string text = std::to_string(mesh.patches.size()) + " patches (" + std::to_string(quads) +
                       " quads, " + with_polygons +
                       std::to_string(mesh.patches.size() - quads - polygons) + " triangles), " +
                       std::to_string(mesh.vertices.size()) + " vertices";
    // Where it lies and in what unit (rad-mesh --unit; meshes before it: metres).
    if (!mesh.vertices.empty()) {
        Vec3 lo = mesh.vertices.front(), hi = lo;
        for (const auto& v : mesh.vertices)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], v[k]);
                hi[k] = std::max(hi[k], v[k]);
            }
        char box[200];
        std::snprintf(box, sizeof box, ", bounding box (%.6g, %.6g, %.6g) to (%.6g, %.6g, %.6g)",
                      lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
        text += box;
    }
    const auto* unit = header.find("unit");
    text += ", unit " + (unit ? *unit : std::string("m (not recorded)"));
    // Mirrors and glass: which materials, of what kind.
    std::string specular;
    for (const auto& m : mesh.materials)
        if (m.specular.any())
            specular += (specular.empty() ? "" : ", ") + m.name + " (" +
                        specular_kind_name(m.specular.kind) + ")";
    if (!specular.empty()) text += "; mirrors and glass: " + specular;
    return text;
}

void form_factor_rows_csv(const FormFactorData& ff, std::ostream& out);

void form_factor_csv(const fs::path& path, std::ostream& out) {
    form_factor_rows_csv(read_form_factors(path), out);
}

void form_factor_part_csv(const fs::path& path, std::ostream& out) {
    form_factor_rows_csv(read_form_factor_part(path), out);
}

std::string form_factor_part_summary(const fs::path& path, Header& header) {
    const auto ff = read_form_factor_part(path, &header);
    return "rows " + header.get("rows_begin", path.string()) + " to " +
           header.get("rows_end", path.string()) + " (end excluded) of " +
           std::to_string(ff.patch_count) + ", " + std::to_string(ff.nonzeros()) +
           " non-zeros; rad-ff --merge joins the parts into the matrix";
}

void form_factor_rows_csv(const FormFactorData& ff, std::ostream& out) {
    char line[128];
    out << kind_info(Kind::FormFactors).csv_columns << '\n';
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k) {
            std::snprintf(line, sizeof line, "%llu,%u,%.9g\n", static_cast<unsigned long long>(i),
                          ff.columns[k], static_cast<double>(ff.values[k]));
            out << line;
        }
        if (!out) return;
    }
}

std::string form_factor_summary(const fs::path& path, Header& header) {
    const auto ff = read_form_factors(path, &header);
    const double n = static_cast<double>(ff.patch_count);
    char text[160];
    std::snprintf(text, sizeof text, "%llu x %llu, %llu non-zeros (%.2f%% dense)",
                  static_cast<unsigned long long>(ff.patch_count),
                  static_cast<unsigned long long>(ff.patch_count),
                  static_cast<unsigned long long>(ff.nonzeros()),
                  n > 0 ? 100.0 * ff.nonzeros() / (n * n) : 0.0);
    std::string out = text;
    if (ff.back_fraction.empty()) {
        out += "; no back-face data (version 1 file)";
    } else {
        std::uint64_t mostly_back = 0;
        double sum = 0, max = 0;
        for (const float f : ff.back_fraction) {
            mostly_back += f > 0.5f;
            sum += f;
            max = std::max(max, double(f));
        }
        std::snprintf(text, sizeof text,
                      "; rays arriving at back faces: mean %.2f%%, max %.2f%%, %llu row(s) "
                      "above 50%%",
                      n > 0 ? 100.0 * sum / n : 0.0, 100.0 * max,
                      static_cast<unsigned long long>(mostly_back));
        out += text;
    }
    return out;
}

void radiosity_csv(const fs::path& path, std::ostream& out) {
    const auto rad = read_radiosity(path);
    char line[160];
    if (rad.group_count() == 0) {
        out << "patch,b_r,b_g,b_b\n";
        for (std::size_t i = 0; i < rad.radiosity.size(); ++i) {
            const auto& b = rad.radiosity[i];
            std::snprintf(line, sizeof line, "%zu,%.10g,%.10g,%.10g\n", i, b[0], b[1], b[2]);
            out << line;
            if (!out) return;
        }
        return;
    }
    // With light groups: one row per patch and group.
    out << "patch,group,b_r,b_g,b_b\n";
    detail::write_group_rows(out, rad.group_names, rad.group_radiosity);
}

std::string radiosity_summary(const fs::path& path, Header& header) {
    const auto rad = read_radiosity(path, &header);
    std::string text = std::to_string(rad.radiosity.size()) + " patches";
    if (rad.group_count()) {
        text += ", " + std::to_string(rad.group_count()) + " light group(s):";
        // A sky's hundreds of groups: the first few and the last.
        const auto& names = rad.group_names;
        for (std::size_t k = 0; k < names.size(); ++k) {
            if (names.size() > 12 && k == 10) {
                text += " ... " + names.back();
                break;
            }
            text += " " + names[k];
        }
    }
    return text;
}

constexpr KindInfo kKinds[] = {
    {Kind::Mesh, "mesh", "patch mesh", 3, 1,
     "patch,group,material,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,e_r,e_g,e_b,corners", mesh_csv,
     mesh_summary},
    {Kind::FormFactors, "formfactors", "form-factor matrix", 3, 1, "row,col,f", form_factor_csv,
     form_factor_summary},
    {Kind::FormFactorPart, "formfactor-part", "form-factor rows (a shard of rad-ff --rows)", 1, 1,
     "row,col,f", form_factor_part_csv, form_factor_part_summary},
    {Kind::Radiosity, "radiosity", "radiosity solution", 2, 1,
     "patch,b_r,b_g,b_b (with light groups: patch,group,b_r,b_g,b_b)", radiosity_csv,
     radiosity_summary},
    {Kind::Links, "links", "link hierarchy (hierarchical form factors)", 2, 2,
     "node,first,count,source,f,r0,r1,r2,r3,s0,s1,s2,s3 (shares in 65535ths)", detail::links_csv,
     detail::links_summary},
    {Kind::Luminaires, "luminaires", "luminaires' direct light per patch (rad-ff --luminaires)", 1,
     1, "patch,group,e_r,e_g,e_b (direct irradiance, W/m^2)", detail::luminaires_csv,
     detail::luminaires_summary},
    {Kind::Sky, "sky", "sky patches' light per patch at unit radiance (rad-ff --sky)", 1, 1,
     "patch,sky_patch,d_r,d_g,d_b (irradiance per unit radiance, sr)", detail::sky_csv,
     detail::sky_summary},
    {Kind::Annual, "annual", "a year of illuminance at sensors (rad-gather --annual)", 1, 1,
     "month,day,hour,occupied,then each sensor's lux", detail::annual_csv, detail::annual_summary},
};

} // namespace

std::span<const KindInfo> kind_table() {
    return kKinds;
}

const KindInfo& kind_info(Kind kind) {
    for (const auto& k : kKinds)
        if (k.kind == kind) return k;
    throw std::logic_error("file kind missing from the kind table");
}

std::string_view kind_name(Kind kind) {
    return kind_info(kind).name;
}
std::string_view kind_description(Kind kind) {
    return kind_info(kind).description;
}
std::uint32_t kind_version(Kind kind) {
    return kind_info(kind).version;
}
bool parse_kind(std::string_view name, Kind& kind) {
    for (const auto& k : kKinds)
        if (k.name == name) {
            kind = k.kind;
            return true;
        }
    return false;
}

void write_csv(const fs::path& path, std::ostream& out) {
    kind_info(read_header(path).kind).write_csv(path, out);
}

} // namespace radfmt
