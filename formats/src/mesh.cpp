// The mesh kind: MeshData's helpers, its writer and its reader (every check a mesh must
// pass), and its CSV and summary for rad-info.
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
using detail::require_count;

namespace {
bool finite(const Vec3& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

std::string number(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}
} // namespace

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

namespace detail {
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
} // namespace detail

} // namespace radfmt
