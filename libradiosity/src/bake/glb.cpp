// Writing a baked mesh as binary glTF 2.0: JSON built with nlohmann-json, one binary chunk.
#include "radfmt/container.hpp"
#include "radiosity/bake.hpp"
#include "radiosity/error.hpp"
#include "radiosity/patch_geometry.hpp"
#include "radiosity/specular_materials.hpp"
#include "radiosity/twins.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>

namespace rad {

namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The binary chunk and the JSON arrays that describe its pieces.
struct GlbBuilder {
    json doc = json::object();
    std::vector<std::uint8_t> bin;

    int add_view(const void* data, std::size_t bytes, int target) {
        while (bin.size() % 4) bin.push_back(0);
        const std::size_t offset = bin.size();
        const auto* p = static_cast<const std::uint8_t*>(data);
        bin.insert(bin.end(), p, p + bytes);
        json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
        if (target) view["target"] = target;
        doc["bufferViews"].push_back(view);
        return static_cast<int>(doc["bufferViews"].size()) - 1;
    }
    int add_floats(const std::vector<float>& values, int width, const char* type, bool bounds) {
        const int view = add_view(values.data(), values.size() * sizeof(float), kArrayBuffer);
        json accessor = {{"bufferView", view},
                         {"componentType", kFloat},
                         {"count", values.size() / width},
                         {"type", type}};
        if (bounds) {
            std::vector<float> lo(width, 0), hi(width, 0);
            for (std::size_t i = 0; i < values.size(); ++i) {
                const auto a = i % width;
                lo[a] = i < std::size_t(width) ? values[i] : std::min(lo[a], values[i]);
                hi[a] = i < std::size_t(width) ? values[i] : std::max(hi[a], values[i]);
            }
            accessor["min"] = lo;
            accessor["max"] = hi;
        }
        doc["accessors"].push_back(accessor);
        return static_cast<int>(doc["accessors"].size()) - 1;
    }
    int add_indices(const std::vector<std::uint32_t>& indices) {
        const int view = add_view(indices.data(), indices.size() * 4, kElementArrayBuffer);
        doc["accessors"].push_back({{"bufferView", view},
                                    {"componentType", kUnsignedInt},
                                    {"count", indices.size()},
                                    {"type", "SCALAR"}});
        return static_cast<int>(doc["accessors"].size()) - 1;
    }
    int add_png(const std::vector<std::uint8_t>& png, const std::string& name) {
        const int view = add_view(png.data(), png.size(), 0);
        doc["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}, {"name", name}});
        return static_cast<int>(doc["images"].size()) - 1;
    }
};

// One primitive's vertices: each patch corner, shared where position, normal and value agree.
struct PrimitiveData {
    // value: COLOR_0 (3), or TEXCOORD_1 and TEXCOORD_0 (2 + 2)
    std::vector<float> position, normal, value;
    std::vector<std::uint32_t> indices;
    std::map<std::array<std::uint32_t, 8>, std::uint32_t> index_of;

    // Every `width`-th float from `first` on, `count` at a time.
    std::vector<float> values(int width, int first, int count) const {
        std::vector<float> out;
        for (std::size_t i = 0; i < value.size(); i += width)
            out.insert(out.end(), value.begin() + long(i) + first,
                       value.begin() + long(i) + first + count);
        return out;
    }
};

struct Corner {
    std::uint32_t mesh_vertex;
    float value[4];
};

// Appends patch `i` as the fan of triangles from its corner 0 (as rad-shade draws it).
void add_patch(PrimitiveData& prim, const radfmt::MeshData& mesh, std::size_t i,
               const std::vector<Corner>& corners, int width) {
    const auto& patch = mesh.patches[i];
    std::vector<std::uint32_t> ids(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) {
        std::array<std::uint32_t, 8> key{};
        const float f[7] = {float(patch.normal[0]), float(patch.normal[1]), float(patch.normal[2]),
                            corners[k].value[0],    corners[k].value[1],    corners[k].value[2],
                            corners[k].value[3]};
        for (int j = 0; j < 7; ++j) key[j] = std::bit_cast<std::uint32_t>(f[j]);
        key[7] = corners[k].mesh_vertex;
        const auto [at, fresh] =
            prim.index_of.emplace(key, static_cast<std::uint32_t>(prim.position.size() / 3));
        ids[k] = at->second;
        if (!fresh) continue;
        const Vec3& p = mesh.vertices[corners[k].mesh_vertex];
        for (int a = 0; a < 3; ++a) prim.position.push_back(float(p[a]));
        for (int a = 0; a < 3; ++a) prim.normal.push_back(float(patch.normal[a]));
        for (int a = 0; a < width; ++a) prim.value.push_back(corners[k].value[a]);
    }
    for (const auto& [a, b, c] : patch_triangles(mesh, i))
        prim.indices.insert(prim.indices.end(), {ids[a], ids[b], ids[c]});
}

// A mirror or glass for an engine that reflects and refracts (the view-dependent light the
// bake cannot hold): a mirror as a smooth metal of its reflectance, glass with
// KHR_materials_transmission and KHR_materials_ior; the chain's own description in extras.
void add_specular_parameters(const radfmt::Specular& s, json& material) {
    if (!s.any()) return;
    material["extras"]["specular"] = specular_summary(s);
    auto& pbr = material["pbrMetallicRoughness"];
    pbr["roughnessFactor"] = s.roughness;
    if (s.mirrors()) {
        pbr["metallicFactor"] = 1.0;
        pbr["baseColorFactor"] = {s.reflectance[0], s.reflectance[1], s.reflectance[2], 1.0};
        return;
    }
    const double through = (s.transmittance[0] + s.transmittance[1] + s.transmittance[2]) / 3;
    material["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", through}};
    material["extensions"]["KHR_materials_ior"] = {{"ior", s.ior}};
}

// The extensions the materials use, for extensionsUsed.
std::vector<std::string> material_extensions(const json& materials) {
    std::vector<std::string> used;
    for (const auto& m : materials)
        if (m.contains("extensions"))
            for (const auto& [name, value] : m["extensions"].items())
                if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
    return used;
}

// The scene's own material for an engine: base colour = reflectance, emission as emissive
// (display values: times the exposure, clamped to 1).
json engine_material_json(const radfmt::Material& m, bool two_sided_sheet, double exposure) {
    json base = json::array(), emissive = json::array();
    for (int c = 0; c < 3; ++c) {
        base.push_back(std::clamp(m.reflectance[c], 0.0, 1.0));
        emissive.push_back(std::clamp(m.emission[c] * exposure, 0.0, 1.0));
    }
    base.push_back(1.0);
    json out = {
        {"name", m.name + (two_sided_sheet ? " (one side of a two-sided sheet)" : "")},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", base}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
        {"emissiveFactor", emissive},
        {"doubleSided", !two_sided_sheet},
        {"extras", {{"reflectance", m.reflectance.c}, {"emission_W_per_m2", m.emission.c}}}};
    add_specular_parameters(m.specular, out);
    return out;
}

json material_json(const radfmt::Material& m, bool two_sided_sheet, int texture) {
    json pbr = {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}},
                {"metallicFactor", 0.0},
                {"roughnessFactor", 1.0}};
    if (texture >= 0) pbr["baseColorTexture"] = {{"index", texture}, {"texCoord", 1}};
    json extras = m.specular.any()
                      ? json{{"reflectance", m.reflectance.c},
                             {"emission_W_per_m2", m.emission.c},
                             {"specular", specular_summary(m.specular)}}
                      : json{{"reflectance", m.reflectance.c}, {"emission_W_per_m2", m.emission.c}};
    // What a pane lets through at normal incidence: the viewer page draws the sky behind it.
    if (m.specular.transmits()) extras["transmittance"] = m.specular.transmittance.c;
    return {{"name", m.name + (two_sided_sheet ? " (one side of a two-sided sheet)" : "")},
            {"pbrMetallicRoughness", pbr},
            {"doubleSided", !two_sided_sheet},
            {"extensions", {{"KHR_materials_unlit", json::object()}}},
            {"extras", extras}};
}

// The primitives, by material and by whether the patch is one side of a two-sided sheet (those
// are one-sided, so a viewer shows the side facing it, as rad-shade does).
std::map<std::pair<std::uint32_t, bool>, PrimitiveData> collect_primitives(const BakeScene& scene) {
    const auto& mesh = *scene.mesh;
    const auto twins = find_twins(mesh);
    const bool lightmap = !scene.lightmap_uv.empty();
    const int width = lightmap ? 4 : 3;
    std::map<std::pair<std::uint32_t, bool>, PrimitiveData> primitives;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& patch = mesh.patches[i];
        const auto ids = mesh.corners(i);
        std::vector<Corner> corners(ids.size());
        for (std::size_t k = 0; k < ids.size(); ++k) {
            corners[k].mesh_vertex = ids[k];
            for (int a = 0; a < width; ++a)
                corners[k].value[a] =
                    !lightmap ? float(std::clamp(scene.corner_colours.at(mesh, i, k)[a], 0.0, 1.0))
                    : a < 2   ? scene.lightmap_uv[i][k][a]
                              : scene.surface_uv[i][k][a - 2];
        }
        add_patch(primitives[{patch.material, twins[i] >= 0}], mesh, i, corners, width);
    }
    return primitives;
}

json build_document(const BakeScene& scene, GlbBuilder& glb) {
    glb.doc["asset"] = {{"version", "2.0"}, {"generator", scene.generator}};
    if (!scene.extras_json.empty())
        glb.doc["asset"]["extras"] = {{"radiosity", json::parse(scene.extras_json)}};
    if (!scene.engine_materials) glb.doc["extensionsUsed"] = {"KHR_materials_unlit"};
    int texture = -1;
    if (!scene.lightmap_uv.empty()) {
        glb.doc["samplers"] = {
            {{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}}};
        glb.doc["textures"] = {
            {{"source", glb.add_png(scene.lightmap_png, "lightmap")}, {"sampler", 0}}};
        texture = 0;
        if (scene.engine_materials) glb.doc["asset"]["extras"]["radiosity"]["lightmap_texture"] = 0;
    }
    json groups = json::array();
    for (const auto& [name, png] : scene.group_lightmaps_png) {
        glb.doc["textures"].push_back(
            {{"source", glb.add_png(png, "lightmap " + name)}, {"sampler", 0}});
        groups.push_back({{"name", name}, {"texture", glb.doc["textures"].size() - 1}});
    }
    if (!groups.empty()) glb.doc["asset"]["extras"]["radiosity"]["light_group_lightmaps"] = groups;
    json primitives = json::array();
    for (auto& [key, prim] : collect_primitives(scene)) {
        const bool lightmap = texture >= 0;
        json attributes = {{"POSITION", glb.add_floats(prim.position, 3, "VEC3", true)},
                           {"NORMAL", glb.add_floats(prim.normal, 3, "VEC3", false)}};
        if (lightmap) {
            attributes["TEXCOORD_0"] = glb.add_floats(prim.values(4, 2, 2), 2, "VEC2", false);
            attributes["TEXCOORD_1"] = glb.add_floats(prim.values(4, 0, 2), 2, "VEC2", false);
        } else {
            attributes["COLOR_0"] = glb.add_floats(prim.value, 3, "VEC3", false);
        }
        const auto& material = scene.mesh->materials[key.first];
        glb.doc["materials"].push_back(
            scene.engine_materials ? engine_material_json(material, key.second, scene.exposure)
                                   : material_json(material, key.second, texture));
        primitives.push_back({{"attributes", attributes},
                              {"indices", glb.add_indices(prim.indices)},
                              {"material", glb.doc["materials"].size() - 1},
                              {"mode", 4}});
    }
    if (scene.engine_materials)
        if (const auto used = material_extensions(glb.doc["materials"]); !used.empty())
            glb.doc["extensionsUsed"] = used;
    glb.doc["meshes"] = {{{"name", "radiosity"}, {"primitives", primitives}}};
    glb.doc["nodes"] = {{{"name", "radiosity"}, {"mesh", 0}}};
    glb.doc["scenes"] = {{{"nodes", {0}}}};
    glb.doc["scene"] = 0;
    while (glb.bin.size() % 4) glb.bin.push_back(0);
    glb.doc["buffers"] = {{{"byteLength", glb.bin.size()}}};
    return glb.doc;
}

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8)
        out.push_back(static_cast<std::uint8_t>(v >> shift));
}

} // namespace

std::vector<std::uint8_t> baked_glb(const BakeScene& scene) {
    GlbBuilder glb;
    std::string text =
        build_document(scene, glb).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    while (text.size() % 4) text.push_back(' '); // the JSON chunk is padded with spaces
    const std::uint64_t total = 12 + 8 + std::uint64_t(text.size()) + 8 + glb.bin.size();
    if (total > 0xFFFFFFFFull)
        throw InputError("the baked mesh needs " + std::to_string(total) +
                         " bytes, more than a glb can hold (4 GiB): bake fewer patches");
    std::vector<std::uint8_t> out;
    out.reserve(total);
    put_u32(out, 0x46546C67); // "glTF"
    put_u32(out, 2);
    put_u32(out, std::uint32_t(total));
    put_u32(out, std::uint32_t(text.size()));
    put_u32(out, 0x4E4F534A); // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    put_u32(out, std::uint32_t(glb.bin.size()));
    put_u32(out, 0x004E4942); // "BIN\0"
    out.insert(out.end(), glb.bin.begin(), glb.bin.end());
    return out;
}

void write_file(const std::string& path, const void* data, std::size_t size) {
    radfmt::write_atomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary);
        out.write(static_cast<const char*>(data), std::streamsize(size));
        out.close();
        if (out.fail()) throw SystemError(path + ": cannot write: " + std::strerror(errno));
    });
}

} // namespace rad
