#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/vec.hpp"

#include <tiny_obj_loader.h>

#include <charconv>
#include <fstream>
#include <set>
#include <sstream>

namespace rad {
namespace fs = std::filesystem;

namespace {

struct LintResult {
    std::vector<int> face_lines;
    std::vector<std::pair<int, std::string>> usemtl; // line, material name
    std::vector<int> faces_without_material;
    std::size_t vertex_count = 0;
};

// Checks what tinyobjloader would accept silently or report without a line number.
LintResult lint_obj(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path.string() + ": cannot open OBJ file");
    LintResult result;
    std::string line;
    int number = 0;
    bool have_material = false;
    while (std::getline(in, line)) {
        ++number;
        while (!line.empty() && (line.back() == '\r' || line.back() == '\\')) line.pop_back();
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword) || keyword[0] == '#') continue;
        if (keyword == "v") {
            double xyz[3];
            for (int k = 0; k < 3; ++k) {
                std::string token;
                if (!(words >> token))
                    throw InputError(FileLoc{path.string(), number}, "vertex needs three numbers");
                if (spells_non_finite(token))
                    throw InputError(FileLoc{path.string(), number},
                                     "vertex coordinate '" + token + "' is not a finite number");
                if (!parse_number(token, xyz[k]))
                    throw InputError(FileLoc{path.string(), number},
                                     "vertex coordinate '" + token +
                                         "' is not a decimal number (such as 1.5 or -2e-3)");
            }
            ++result.vertex_count;
        } else if (keyword == "f") {
            std::string token;
            int corners = 0;
            while (words >> token) {
                long index = 0;
                const auto slash = token.find('/');
                const auto head = token.substr(0, slash);
                auto [ptr, ec] = std::from_chars(head.data(), head.data() + head.size(), index);
                if (ec != std::errc() || ptr != head.data() + head.size())
                    throw InputError(FileLoc{path.string(), number},
                                     "bad vertex reference '" + token + "'");
                const long count = static_cast<long>(result.vertex_count);
                const long resolved = index < 0 ? count + index + 1 : index;
                if (index == 0 || resolved < 1 || resolved > count)
                    throw InputError(FileLoc{path.string(), number},
                                     "face refers to vertex " + std::to_string(index) +
                                         ", but only " + std::to_string(count) +
                                         " vertices are defined");
                ++corners;
            }
            if (corners < 3)
                throw InputError(FileLoc{path.string(), number},
                                 "face has " + std::to_string(corners) +
                                     " vertices; at least 3 are needed");
            if (!have_material)
                throw InputError(FileLoc{path.string(), number},
                                 "face has no material (put 'usemtl NAME' before it)");
            result.face_lines.push_back(number);
        } else if (keyword == "usemtl") {
            std::string name;
            std::getline(words >> std::ws, name);
            result.usemtl.emplace_back(number, name);
            have_material = true;
        } else if (keyword == "mtllib") {
            std::string name;
            std::getline(words >> std::ws, name);
            const auto mtl = path.parent_path() / name;
            if (!fs::is_regular_file(mtl))
                throw InputError(FileLoc{path.string(), number}, "material library '" + name +
                                                                     "' not found (looked for " +
                                                                     mtl.string() + ")");
        }
    }
    return result;
}

} // namespace

Scene load_obj(const fs::path& path) {
    if (!fs::is_regular_file(path)) throw InputError(path.string() + ": no such OBJ file");
    const auto lint = lint_obj(path);

    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    config.vertex_color = false;
    config.mtl_search_path = path.parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path.string(), config))
        throw InputError(path.string() + ": " + reader.Error());

    Scene scene;
    scene.path = path.string();
    const auto& attrib = reader.GetAttrib();
    for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        scene.vertices.push_back(
            {attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]});

    std::set<std::string> known;
    for (const auto& m : reader.GetMaterials()) {
        radfmt::Material material;
        material.name = m.name;
        for (int k = 0; k < 3; ++k) {
            material.reflectance[k] = m.diffuse[k];
            material.emission[k] = m.emission[k];
        }
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(material.reflectance[k]) || material.reflectance[k] < 0 ||
                !std::isfinite(material.emission[k]) || material.emission[k] < 0)
                throw InputError(path.string() + ": material '" + m.name +
                                 "' has a negative or non-finite Kd or Ke");
        }
        known.insert(m.name);
        scene.materials.push_back(material);
    }
    for (const auto& [line, name] : lint.usemtl)
        if (!known.count(name))
            throw InputError(FileLoc{path.string(), line},
                             "unknown material '" + name + "' (not defined in any mtllib)");

    std::size_t face_number = 0;
    const bool lines_match = [&] {
        std::size_t faces = 0;
        for (const auto& s : reader.GetShapes()) faces += s.mesh.num_face_vertices.size();
        return faces == lint.face_lines.size();
    }();
    for (const auto& shape : reader.GetShapes()) {
        const std::string group_name = shape.name.empty() ? "default" : shape.name;
        std::uint32_t group = 0;
        for (; group < scene.groups.size(); ++group)
            if (scene.groups[group] == group_name) break;
        if (group == scene.groups.size()) scene.groups.push_back(group_name);
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face_number) {
            Polygon poly;
            poly.group = group;
            poly.line = lines_match ? lint.face_lines[face_number] : 0;
            const int count = shape.mesh.num_face_vertices[f];
            bool all_normals = true;
            Vec3 vn{0, 0, 0};
            for (int k = 0; k < count; ++k) {
                const auto& index = shape.mesh.indices[offset + k];
                poly.vertices.push_back(static_cast<std::uint32_t>(index.vertex_index));
                if (index.normal_index < 0 ||
                    3 * std::size_t(index.normal_index) + 2 >= attrib.normals.size()) {
                    all_normals = false;
                    continue;
                }
                for (int c = 0; c < 3; ++c) vn[c] += attrib.normals[3 * index.normal_index + c];
            }
            if (all_normals) poly.vn_sum = vn;
            offset += count;
            const int material = shape.mesh.material_ids[f];
            if (material < 0 || material >= static_cast<int>(scene.materials.size()))
                throw InputError(FileLoc{path.string(), poly.line}, "face has no known material");
            poly.material = static_cast<std::uint32_t>(material);
            scene.polygons.push_back(std::move(poly));
        }
    }
    if (scene.polygons.empty()) throw InputError(path.string() + ": scene is empty (no faces)");
    // Record the MTL files for the provenance hashes.
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string keyword, name;
        if (words >> keyword && keyword == "mtllib") {
            std::getline(words >> std::ws, name);
            while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
            scene.material_files.push_back((path.parent_path() / name).string());
        }
    }
    return scene;
}

} // namespace rad
