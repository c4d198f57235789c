#include "radfmt/kinds.hpp"

#include <cmath>
#include <cstdio>
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
    return "xxh64:" + hash_hex(w.hash());
}

static std::string number(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

// ---- mesh ----

void write_mesh(const fs::path& path, Header header, const MeshData& mesh) {
    header.kind = Kind::Mesh;
    header.set("patches", std::to_string(mesh.patches.size()));
    header.set("vertices", std::to_string(mesh.vertices.size()));
    header.set("groups", std::to_string(mesh.groups.size()));
    header.set("materials", std::to_string(mesh.materials.size()));
    header.set("total_area", number(mesh.total_area()));
    header.set("geometry_hash", mesh.geometry_hash());

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
    w.u64(mesh.groups.size());
    for (const auto& g : mesh.groups) w.string(g);
    w.u64(mesh.materials.size());
    for (const auto& m : mesh.materials) {
        w.string(m.name);
        w.array(std::span<const double>(m.reflectance));
        w.array(std::span<const double>(m.emission));
    }
    write_file(path, std::move(header), w);
}

MeshData read_mesh(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Mesh;
    auto file = read_file(path, &kind);
    BodyReader r(file.body, path.string());
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
    const auto ng = r.count(8, "groups");
    for (std::uint64_t i = 0; i < ng; ++i) mesh.groups.push_back(r.string());
    const auto nm = r.count(8 + 48, "materials");
    for (std::uint64_t i = 0; i < nm; ++i) {
        Material m;
        m.name = r.string();
        const auto rho = r.array<double>(3, "reflectance");
        const auto e = r.array<double>(3, "emission");
        for (int k = 0; k < 3; ++k) {
            m.reflectance[k] = rho[k];
            m.emission[k] = e[k];
        }
        mesh.materials.push_back(std::move(m));
    }
    r.expect_end();
    mesh.patches.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        auto& p = mesh.patches[i];
        for (int k = 0; k < 4; ++k) {
            p.corners[k] = corners[4 * i + k];
            if ((p.corners[k] >= nv && !(k == 3 && p.corners[k] == kNoVertex)))
                r.fail("patch " + std::to_string(i) + " refers to vertex " +
                       std::to_string(p.corners[k]) + " of " + std::to_string(nv));
        }
        p.group = group[i];
        p.material = material[i];
        if (p.group >= ng || p.material >= nm)
            r.fail("patch " + std::to_string(i) + " refers to a missing group or material");
        p.area = area[i];
        for (int k = 0; k < 3; ++k) {
            p.centroid[k] = centroid[3 * i + k];
            p.normal[k] = normal[3 * i + k];
        }
    }
    if (header_out) *header_out = std::move(file.header);
    return mesh;
}

// ---- form factors ----

void write_form_factors(const fs::path& path, Header header, const FormFactorData& ff) {
    header.kind = Kind::FormFactors;
    header.set("patches", std::to_string(ff.patch_count));
    header.set("nonzeros", std::to_string(ff.nonzeros()));
    BodyWriter w;
    w.u64(ff.patch_count);
    w.u64(ff.nonzeros());
    w.array(ff.row_start);
    w.array(ff.columns);
    w.array(ff.values);
    write_file(path, std::move(header), w);
}

FormFactorData read_form_factors(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::FormFactors;
    auto file = read_file(path, &kind);
    BodyReader r(file.body, path.string());
    FormFactorData ff;
    ff.patch_count = r.count(8, "rows");
    const auto nnz = r.count(8, "non-zeros");
    ff.row_start = r.array<std::uint64_t>(ff.patch_count + 1, "row starts");
    ff.columns = r.array<std::uint32_t>(nnz, "columns");
    ff.values = r.array<float>(nnz, "values");
    r.expect_end();
    if (ff.row_start.front() != 0 || ff.row_start.back() != nnz)
        r.fail("row starts do not span the non-zeros");
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        if (ff.row_start[i] > ff.row_start[i + 1])
            r.fail("row starts decrease at row " + std::to_string(i));
    }
    for (auto c : ff.columns)
        if (c >= ff.patch_count) r.fail("column " + std::to_string(c) + " out of range");
    if (header_out) *header_out = std::move(file.header);
    return ff;
}

// ---- radiosity ----

void write_radiosity(const fs::path& path, Header header, const RadiosityData& rad) {
    header.kind = Kind::Radiosity;
    header.set("patches", std::to_string(rad.radiosity.size()));
    BodyWriter w;
    w.u64(rad.radiosity.size());
    w.array(rad.radiosity);
    write_file(path, std::move(header), w);
}

RadiosityData read_radiosity(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Radiosity;
    auto file = read_file(path, &kind);
    BodyReader r(file.body, path.string());
    RadiosityData rad;
    const auto n = r.count(24, "patches");
    rad.radiosity = r.array<Rgb>(n, "radiosity");
    r.expect_end();
    if (header_out) *header_out = std::move(file.header);
    return rad;
}

// ---- CSV ----

void write_csv(const fs::path& path, std::ostream& out) {
    const auto header = read_header(path);
    char line[512];
    switch (header.kind) {
    case Kind::Mesh: {
        const auto mesh = read_mesh(path);
        out << "patch,group,material,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,e_r,e_g,e_b\n";
        for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
            const auto& p = mesh.patches[i];
            const auto& m = mesh.materials[p.material];
            std::snprintf(line, sizeof line,
                          "%zu,%s,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%."
                          "10g,%.10g,%.10g\n",
                          i, mesh.groups[p.group].c_str(), m.name.c_str(), p.area, p.centroid[0],
                          p.centroid[1], p.centroid[2], p.normal[0], p.normal[1], p.normal[2],
                          m.reflectance[0], m.reflectance[1], m.reflectance[2], m.emission[0],
                          m.emission[1], m.emission[2]);
            out << line;
        }
        break;
    }
    case Kind::FormFactors: {
        const auto ff = read_form_factors(path);
        out << "row,col,f\n";
        for (std::uint64_t i = 0; i < ff.patch_count; ++i)
            for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k) {
                std::snprintf(line, sizeof line, "%llu,%u,%.9g\n",
                              static_cast<unsigned long long>(i), ff.columns[k],
                              static_cast<double>(ff.values[k]));
                out << line;
            }
        break;
    }
    case Kind::Radiosity: {
        const auto rad = read_radiosity(path);
        out << "patch,b_r,b_g,b_b\n";
        for (std::size_t i = 0; i < rad.radiosity.size(); ++i) {
            const auto& b = rad.radiosity[i];
            std::snprintf(line, sizeof line, "%zu,%.10g,%.10g,%.10g\n", i, b[0], b[1], b[2]);
            out << line;
        }
        break;
    }
    }
}

} // namespace radfmt
