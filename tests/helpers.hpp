// Shared helpers for the tests: temporary folders and small scenes written as OBJ text.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/vec.hpp"

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace testing_helpers {
namespace fs = std::filesystem;

inline fs::path temp_dir(const std::string& name) {
    static std::random_device rd;
    auto dir = fs::temp_directory_path() / ("radiosity-test-" + name + "-" + std::to_string(rd()));
    fs::create_directories(dir);
    return dir;
}

inline void write_text(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

inline const char* kGreyMtl =
    "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.2 0.2 0.2\nKe 10 8 6\n";

// Writes OBJ + MTL and loads them.
inline rad::Scene scene_from_obj(const std::string& obj, const std::string& mtl = kGreyMtl,
                                 const std::string& name = "scene") {
    const auto dir = temp_dir(name);
    write_text(dir / "scene.mtl", mtl);
    write_text(dir / "scene.obj", "mtllib scene.mtl\n" + obj);
    return rad::load_obj(dir / "scene.obj");
}

// A closed unit cube with inward-facing quads (size s), all of one material.
inline std::string cube_obj(double s = 1.0, const std::string& material = "grey") {
    std::string v;
    for (int i = 0; i < 8; ++i)
        v += "v " + std::to_string(s * (i & 1)) + " " + std::to_string(s * ((i >> 1) & 1)) + " " +
             std::to_string(s * ((i >> 2) & 1)) + "\n";
    // Vertex index = 1 + x + 2y + 4z; faces wound so normals point into the cube.
    return v + "usemtl " + material + "\n" +
           "g bottom\nf 1 2 4 3\n" // z=0, normal +z
           "g top\nf 5 7 8 6\n"    // z=1, normal -z
           "g front\nf 1 5 6 2\n"  // y=0, normal +y
           "g back\nf 3 4 8 7\n"   // y=1, normal -y
           "g left\nf 1 3 7 5\n"   // x=0, normal +x
           "g right\nf 2 6 8 4\n"; // x=1, normal -x
}

// Appends to `m` a polygon patch over new vertices at `corners` (star-shaped from the first),
// with the area, centroid and normal given (worked out by the test, not from its corners).
inline void add_polygon_patch(radfmt::MeshData& m, const std::vector<radfmt::Vec3>& corners,
                              double area, const radfmt::Vec3& centroid, const radfmt::Vec3& normal,
                              std::uint32_t material = 0) {
    std::vector<std::uint32_t> ids;
    for (const auto& corner : corners) {
        ids.push_back(static_cast<std::uint32_t>(m.vertices.size()));
        m.vertices.push_back(corner);
    }
    radfmt::Patch polygon;
    m.set_corners(polygon, ids, true);
    polygon.material = material;
    polygon.area = area;
    polygon.centroid = centroid;
    polygon.normal = normal;
    m.patches.push_back(polygon);
}

// Patch 0: a polygon patch at z = 0 facing up, of `outline`'s corners (x, y), star-shaped from
// the first; patch 1: the 2 x 2 square [0, 2]^2 at z = 1 facing down, a quad.
inline radfmt::MeshData polygon_under_square(const std::vector<std::array<double, 2>>& outline,
                                             double area, const radfmt::Vec3& centroid) {
    radfmt::MeshData m;
    m.groups = {"g"};
    m.materials = {{"grey", {0.5, 0.5, 0.5}, {0, 0, 0}, {}}};
    std::vector<radfmt::Vec3> corners;
    for (const auto& [x, y] : outline) corners.push_back({x, y, 0});
    add_polygon_patch(m, corners, area, centroid, {0, 0, 1});
    const auto top = static_cast<std::uint32_t>(m.vertices.size());
    for (const auto& [x, y] : std::vector<std::array<double, 2>>{{0, 0}, {0, 2}, {2, 2}, {2, 0}})
        m.vertices.push_back({x, y, 1});
    radfmt::Patch square;
    square.corners = {top, top + 1, top + 2, top + 3};
    square.area = 4;
    square.centroid = {1, 1, 1};
    square.normal = {0, 0, -1};
    m.patches.push_back(square);
    return m;
}

inline radfmt::MeshData mesh_from_obj(const std::string& obj, double max_edge = 0) {
    rad::SubdivisionOptions options;
    options.max_edge = max_edge;
    return rad::subdivide(scene_from_obj(obj), options);
}

#ifdef RADIOSITY_SOURCE_DIR
// The project's Cornell box (scenes/cornell) meshed at `max_edge`.
inline radfmt::MeshData cornell_mesh(double max_edge) {
    rad::SubdivisionOptions options;
    options.max_edge = max_edge;
    return rad::subdivide(
        rad::load_obj(fs::path(RADIOSITY_SOURCE_DIR) / "scenes/cornell/cornell.obj"), options);
}
#endif

// Appends one face to OBJ text: "g GROUP" (when given), "usemtl MATERIAL", its vertices and
// an 'f' line over them; `count` is the number of vertices written so far. Appended piece by
// piece (GCC 12 warns falsely about "literal" + string&&).
inline void append_obj_face(std::string& obj, int& count, const std::vector<rad::Vec3>& corners,
                            const std::string& material, const std::string& group = "") {
    if (!group.empty()) {
        obj += "g ";
        obj += group;
        obj += '\n';
    }
    obj += "usemtl ";
    obj += material;
    obj += '\n';
    for (const auto& c : corners) {
        obj += 'v';
        for (double x : c) {
            obj += ' ';
            obj += std::to_string(x);
        }
        obj += '\n';
    }
    obj += 'f';
    for (std::size_t k = 0; k < corners.size(); ++k) {
        obj += ' ';
        obj += std::to_string(++count);
    }
    obj += '\n';
}

} // namespace testing_helpers
