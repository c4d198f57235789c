// Scenes in the formats assimp reads (glTF 2.0, PLY, COLLADA, FBX, ...): the same Scene as
// an OBJ gives, so everything after reading (orientation, subdivision) is shared.
#include "import/isolated.hpp"
#include "import/precheck.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/specular_materials.hpp"
#include "radiosity/texture.hpp"
#include "radiosity/vec.hpp"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

namespace rad {
namespace fs = std::filesystem;

namespace {

using import::lower_extension;

// What assimp 5.2 does not give of a glTF file: each material's emissiveStrength
// (KHR_materials_emissive_strength), and the files it refers to (buffers, images), which the
// mesh's provenance must hash. From the JSON of a .gltf, or the first chunk of a .glb.
struct GltfExtras {
    std::vector<double> emissive_strength; // per glTF material
    // Per glTF material, its metallic-roughness, transmission, ior and volume (the base
    // colour is left to assimp, which averages its texture).
    std::vector<PbrSpecularInput> pbr;
    std::vector<std::string> files; // relative to the scene's folder
};

// A number at `key` of a JSON object, or `fallback`.
double json_number(const nlohmann::json& object, const char* key, double fallback) {
    if (!object.is_object() || !object.contains(key) || !object[key].is_number()) return fallback;
    const double value = object[key].get<double>();
    return std::isfinite(value) ? value : fallback;
}

// glTF's defaults: metallic 1, roughness 1 (a rough metal, kept diffuse).
PbrSpecularInput pbr_of(const nlohmann::json& material) {
    PbrSpecularInput in;
    const nlohmann::json none = nlohmann::json::object();
    const auto& pbr = material.is_object() && material.contains("pbrMetallicRoughness")
                          ? material["pbrMetallicRoughness"]
                          : none;
    in.metallic = json_number(pbr, "metallicFactor", 1);
    in.roughness = json_number(pbr, "roughnessFactor", 1);
    if (!material.is_object() || !material.contains("extensions")) return in;
    const auto& extensions = material["extensions"];
    if (!extensions.is_object()) return in;
    const auto extension = [&](const char* name) -> const nlohmann::json& {
        return extensions.contains(name) ? extensions[name] : none;
    };
    in.transmission = json_number(extension("KHR_materials_transmission"), "transmissionFactor", 0);
    in.ior = json_number(extension("KHR_materials_ior"), "ior", 1.5);
    if (extensions.contains("KHR_materials_volume"))
        in.thickness = json_number(extension("KHR_materials_volume"), "thicknessFactor", 0);
    return in;
}
GltfExtras gltf_extras(const fs::path& path) {
    GltfExtras extras;
    const auto ext = lower_extension(path);
    if (ext != ".gltf" && ext != ".glb") return extras;
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string json_text;
    if (ext == ".glb") {
        // 12-byte header, then chunk 0: u32 length, u32 type "JSON", the text.
        if (bytes.size() < 20 || bytes.compare(16, 4, "JSON") != 0) return extras;
        std::uint32_t length = 0;
        std::memcpy(&length, bytes.data() + 12, 4);
        if (20 + std::size_t(length) > bytes.size()) return extras;
        json_text = bytes.substr(20, length);
    } else {
        json_text = std::move(bytes);
    }
    const auto json = nlohmann::json::parse(json_text, nullptr, false);
    if (json.is_discarded() || !json.is_object()) return extras;
    if (json.contains("materials") && json["materials"].is_array())
        for (const auto& material : json["materials"]) {
            double strength = 1;
            if (material.is_object() && material.contains("extensions")) {
                const auto& extensions = material["extensions"];
                if (extensions.is_object() &&
                    extensions.contains("KHR_materials_emissive_strength")) {
                    const auto& khr = extensions["KHR_materials_emissive_strength"];
                    if (khr.is_object() && khr.contains("emissiveStrength") &&
                        khr["emissiveStrength"].is_number())
                        strength = khr["emissiveStrength"].get<double>();
                }
            }
            extras.emissive_strength.push_back(strength);
            extras.pbr.push_back(pbr_of(material));
        }
    for (const char* list : {"buffers", "images"})
        if (json.contains(list) && json[list].is_array())
            for (const auto& item : json[list])
                if (item.is_object() && item.contains("uri") && item["uri"].is_string()) {
                    const auto uri = item["uri"].get<std::string>();
                    if (uri.rfind("data:", 0) != 0) extras.files.push_back(uri);
                }
    return extras;
}

Vec3 transform_point(const aiMatrix4x4& m, const aiVector3D& v) {
    return {m.a1 * v.x + m.a2 * v.y + m.a3 * v.z + m.a4,
            m.b1 * v.x + m.b2 * v.y + m.b3 * v.z + m.b4,
            m.c1 * v.x + m.c2 * v.y + m.c3 * v.z + m.c4};
}

// The texture of `type` (or nothing), averaged: embedded ("*0", or a name an embedded
// texture carries) or a file next to the scene.
void apply_texture(const aiScene& scene, const aiMaterial& material, aiTextureType type,
                   const fs::path& scene_path, const SceneOptions& options, radfmt::Material& out,
                   SceneReport& report, std::vector<std::string>& files) {
    const bool allow_outside = options.allow_outside_refs;
    aiString name;
    if (material.GetTexture(type, 0, &name) != AI_SUCCESS || name.length == 0) return;
    const std::string texture_name = name.C_Str();
    std::string problem;
    std::optional<radfmt::Rgb> mean;
    if (const aiTexture* embedded = scene.GetEmbeddedTexture(name.C_Str())) {
        if (embedded->mHeight == 0) {
            mean = mean_texture_colour(
                std::span<const unsigned char>(
                    reinterpret_cast<const unsigned char*>(embedded->pcData), embedded->mWidth),
                problem, options.max_texture_pixels);
        } else {
            problem = "uncompressed embedded textures are not read";
        }
    } else {
        const auto path =
            import::referenced_file(scene_path, scene_path.parent_path(), texture_name,
                                    "material '" + out.name + "' texture", allow_outside);
        if (!fs::is_regular_file(path)) {
            report.texture_problems.push_back(out.name + ": texture " + path.string() +
                                              " not found");
            return;
        }
        mean = mean_texture_colour(path, problem, options.max_texture_pixels);
        if (mean) files.push_back(path.string());
    }
    if (!mean) {
        report.texture_problems.push_back(out.name + ": texture " + texture_name + " unreadable (" +
                                          problem + ")");
        return;
    }
    for (int k = 0; k < 3; ++k) out.reflectance[k] *= (*mean)[k];
    report.textures_averaged.push_back(out.name + ": " + texture_name);
}

// One assimp material as the scene's: base colour (or diffuse) and its texture's mean as the
// reflectance, emissive times its strength as the emission.
radfmt::Material material_of(const aiScene& ai, unsigned m, double strength, const fs::path& path,
                             const SceneOptions& options, SceneReport& report, Scene& scene) {
    const aiMaterial& material = *ai.mMaterials[m];
    radfmt::Material out;
    aiString name;
    out.name = material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0
                   ? name.C_Str()
                   : "material" + std::to_string(m);
    aiColor4D base(1, 1, 1, 1);
    aiColor3D diffuse(1, 1, 1);
    if (material.Get(AI_MATKEY_BASE_COLOR, base) == AI_SUCCESS) {
        out.reflectance = {{base.r, base.g, base.b}};
        apply_texture(ai, material, aiTextureType_BASE_COLOR, path, options, out, report,
                      scene.material_files);
    } else {
        if (material.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS)
            out.reflectance = {{diffuse.r, diffuse.g, diffuse.b}};
        apply_texture(ai, material, aiTextureType_DIFFUSE, path, options, out, report,
                      scene.material_files);
    }
    aiColor3D emissive(0, 0, 0);
    material.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    out.emission = {{emissive.r * strength * options.emission_scale,
                     emissive.g * strength * options.emission_scale,
                     emissive.b * strength * options.emission_scale}};
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(out.reflectance[k]) || out.reflectance[k] < 0 ||
            !std::isfinite(out.emission[k]) || out.emission[k] < 0)
            throw InputError(path.string() + ": material '" + out.name +
                             "' has a negative or non-finite colour or emission");
    return out;
}

void add_materials(const aiScene& ai, const fs::path& path, const SceneOptions& options,
                   Scene& scene, SceneReport& report) {
    const auto extras = gltf_extras(path);
    for (const auto& file : extras.files)
        if (fs::is_regular_file(path.parent_path() / file))
            scene.material_files.push_back((path.parent_path() / file).string());
    for (unsigned m = 0; m < ai.mNumMaterials; ++m) {
        float intensity = 1;
        ai.mMaterials[m]->Get(AI_MATKEY_EMISSIVE_INTENSITY, intensity);
        const auto& strengths = extras.emissive_strength;
        const double strength = m < strengths.size() ? strengths[m] : double(intensity);
        auto material = material_of(ai, m, strength, path, options, report, scene);
        if (m < extras.pbr.size()) {
            auto pbr = extras.pbr[m];
            pbr.base = material.reflectance;
            material.specular = specular_from_pbr(pbr, material.reflectance);
            if (const auto fitted = fit_specular_energy(material); !fitted.empty())
                report.materials_changed.push_back("material '" + material.name + "': " + fitted);
        }
        scene.materials.push_back(std::move(material));
        scene.material_sources.push_back({});
    }
    if (scene.materials.empty()) {
        scene.materials.push_back({"default", options.default_reflectance, {}, {}});
        scene.material_sources.push_back({});
        report.default_material = "default";
    }
}

// One node's mesh, placed by `transform` (faces reversed when it mirrors), in group `group`.
void add_mesh(const aiMesh& mesh, const aiMatrix4x4& transform, std::uint32_t group,
              const std::string& node_name, const fs::path& path, Scene& scene) {
    // A mirroring transform (negative determinant) turns faces inside out: undo it.
    const bool mirrored = transform.Determinant() < 0;
    // Normals go through the inverse transpose of the transform's linear part.
    aiMatrix3x3 normal_transform(transform);
    normal_transform.Inverse().Transpose();
    const auto base = static_cast<std::uint32_t>(scene.vertices.size());
    scene.face_ranges.push_back({static_cast<int>(scene.polygons.size()) + 1,
                                 "node '" + node_name + "', mesh '" + mesh.mName.C_Str() + "'"});
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const Vec3 p = transform_point(transform, mesh.mVertices[v]);
        if (!finite(p))
            throw InputError(path.string() + ": mesh '" + mesh.mName.C_Str() +
                             "' has a vertex that is not a finite number");
        scene.vertices.push_back(p);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices < 3) continue;
        Polygon polygon;
        polygon.line = static_cast<int>(scene.polygons.size()) + 1; // faces numbered
        polygon.group = group;
        polygon.material = std::min<std::uint32_t>(
            mesh.mMaterialIndex, static_cast<std::uint32_t>(scene.materials.size() - 1));
        for (unsigned i = 0; i < face.mNumIndices; ++i)
            polygon.vertices.push_back(base + face.mIndices[i]);
        if (mesh.HasNormals()) // what the file says the front is (as OBJ's vn)
            for (unsigned i = 0; i < face.mNumIndices; ++i) {
                const aiVector3D n = normal_transform * mesh.mNormals[face.mIndices[i]];
                polygon.vn_sum = polygon.vn_sum + Vec3{n.x, n.y, n.z};
            }
        if (mirrored) std::reverse(polygon.vertices.begin(), polygon.vertices.end());
        scene.polygons.push_back(std::move(polygon));
    }
}

// Every node's meshes, placed by the product of the transforms down to it; a node's group is
// its name, or its parent's when it has none.
void add_nodes(const aiScene& ai, const aiNode& node, const aiMatrix4x4& parent,
               const std::string& parent_name, const fs::path& path,
               std::map<std::string, std::uint32_t>& group_of, Scene& scene) {
    const aiMatrix4x4 transform = parent * node.mTransformation;
    std::string name = node.mName.length ? node.mName.C_Str() : parent_name;
    if (name.empty()) name = "default";
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
        const aiMesh& mesh = *ai.mMeshes[node.mMeshes[k]];
        if (!(mesh.mPrimitiveTypes & (aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON)))
            continue;
        const auto [it, added] =
            group_of.try_emplace(name, static_cast<std::uint32_t>(scene.groups.size()));
        if (added) scene.groups.push_back(name);
        add_mesh(mesh, transform, it->second, name, path, scene);
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        add_nodes(ai, *node.mChildren[c], transform, name, path, group_of, scene);
}

// The faces the node hierarchy places: each node's meshes' faces, for every node (an instanced
// mesh counts at each of its nodes). Saturates instead of overflowing.
std::uint64_t placed_faces(const aiScene& ai, const aiNode& node, int depth = 0) {
    std::uint64_t faces = 0;
    for (unsigned m = 0; m < node.mNumMeshes; ++m)
        if (node.mMeshes[m] < ai.mNumMeshes) faces += ai.mMeshes[node.mMeshes[m]]->mNumFaces;
    if (depth < 2000)
        for (unsigned c = 0; c < node.mNumChildren; ++c)
            faces = std::min<std::uint64_t>(faces + placed_faces(ai, *node.mChildren[c], depth + 1),
                                            std::uint64_t(1) << 62);
    return faces;
}

// The only files assimp may open: the scene itself and regular files inside its folder (unless
// --allow-outside-refs), decided on the path as assimp opens it (after its own clean-up of
// separators and escapes, relative to the working folder as its default IO opens it), with
// links resolved. Checking the file's text beforehand guessed how assimp would read a name
// ("..\\x.bin" passed as an odd name inside the folder, then assimp opened ../x.bin); here
// the check and the open are one. What it refuses it remembers, for the message.
class FolderBoundIO final : public Assimp::DefaultIOSystem {
  public:
    FolderBoundIO(const fs::path& scene, bool allow_outside)
        : scene_(fs::weakly_canonical(scene)), folder_(scene_.parent_path()),
          allow_outside_(allow_outside) {}
    bool Exists(const char* file) const override {
        return allowed(file) && Assimp::DefaultIOSystem::Exists(file);
    }
    Assimp::IOStream* Open(const char* file, const char* mode = "rb") override {
        if (!allowed(file) || (mode && std::strpbrk(mode, "wa+"))) {
            refused_.push_back(file);
            return nullptr;
        }
        return Assimp::DefaultIOSystem::Open(file, mode);
    }
    const std::vector<std::string>& refused() const { return refused_; }
    bool outside_allowed() const { return allow_outside_; }

  private:
    bool allowed(const char* file) const {
        if (!file) return false;
        std::error_code ec;
        const auto path = fs::weakly_canonical(fs::path(file), ec);
        if (ec) return false;
        if (path == scene_) return true;
        const auto status = fs::status(path, ec);
        // A FIFO, device or folder is never opened (a FIFO blocks until the import timeout).
        if (!ec && fs::exists(status) && !fs::is_regular_file(status)) return false;
        if (allow_outside_) return true;
        const auto [end, at] =
            std::mismatch(folder_.begin(), folder_.end(), path.begin(), path.end());
        return end == folder_.end();
    }
    fs::path scene_, folder_;
    bool allow_outside_;
    mutable std::vector<std::string> refused_;
};

} // namespace

namespace {
// The file's lights (glTF's KHR_lights_punctual, COLLADA's and FBX's lamps): not surfaces, so
// nothing the chain lights with; each "'NAME' (point) at (x, y, z)", where its node puts it.
std::vector<std::string> lights_of(const aiScene& ai) {
    static const char* kind[] = {"undefined", "directional", "point", "spot", "ambient", "area"};
    std::vector<std::string> out;
    for (unsigned k = 0; k < ai.mNumLights; ++k) {
        const auto& light = *ai.mLights[k];
        aiVector3D at = light.mPosition;
        aiMatrix4x4 place;
        for (const aiNode* node = ai.mRootNode->FindNode(light.mName); node; node = node->mParent)
            place = node->mTransformation * place;
        at = place * at;
        const unsigned type = static_cast<unsigned>(light.mType);
        char text[300];
        std::snprintf(text, sizeof text, "'%.100s' (%s) at (%.4g, %.4g, %.4g)", light.mName.C_Str(),
                      type < 6 ? kind[type] : "light", at.x, at.y, at.z);
        out.push_back(text);
    }
    return out;
}
} // namespace

Scene load_with_assimp(const fs::path& path, const SceneOptions& options, SceneReport* report_out) {
    if (!fs::is_regular_file(path)) throw InputError(path.string() + ": no such scene file");
    SceneReport local_report;
    SceneReport& report = report_out ? *report_out : local_report;
    Assimp::Importer importer;
    auto* io = new FolderBoundIO(path, options.allow_outside_refs); // the importer owns it
    importer.SetIOHandler(io);
    // Vertices shared by position and attributes, as an OBJ's are; faces kept as written
    // (quads stay quads); lines and points sorted out.
    const aiScene* ai =
        importer.ReadFile(path.string(), aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                                             aiProcess_ValidateDataStructure);
    // assimp catches its own out-of-memory: it is one still (the isolated import says so).
    if (!ai && std::strstr(importer.GetErrorString(), "bad_alloc")) throw std::bad_alloc();
    if (!io->refused().empty()) // even when assimp went on without the file
        throw InputError(path.string() + ": the importer asked for '" + io->refused().front() +
                         "', which " +
                         (io->outside_allowed() ? std::string("is not a regular file (a FIFO, "
                                                              "device or folder is never opened)")
                                                : std::string("lies outside the scene's folder "
                                                              "or is not a regular file (a FIFO, "
                                                              "device or folder is never opened; "
                                                              "--allow-outside-refs allows files "
                                                              "outside)")) +
                         "; nothing was written");
    if (!ai || !ai->mRootNode || (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
        throw InputError(path.string() + ": cannot read the scene (" + importer.GetErrorString() +
                         ")");
    // Instances counted before they are expanded: the faces every node places.
    check_mesh_memory(placed_faces(*ai, *ai->mRootNode), options.max_memory, path.string());
    Scene scene;
    scene.path = path.string();
    add_materials(*ai, path, options, scene, report);
    std::map<std::string, std::uint32_t> group_of;
    add_nodes(*ai, *ai->mRootNode, aiMatrix4x4(), "", path, group_of, scene);
    report.lights = lights_of(*ai);
    if (scene.polygons.empty())
        throw InputError(path.string() + ": scene is empty (no faces; points and lines are not "
                                         "surfaces)");
    return scene;
}

// assimp runs isolated (import/isolated.hpp), after our own checks of what would hang or
// crash it or have it read outside the scene's folder.
Scene load_scene(const fs::path& path, const SceneOptions& options, SceneReport* report) {
    if (lower_extension(path) == ".obj") return load_obj(path, options, report);
    import::check_before_import(path, options);
    if (!options.import.isolate) return load_with_assimp(path, options, report);
    ImportLimits limits = options.import;
    if (limits.memory_bytes == 0)
        limits.memory_bytes =
            static_cast<std::uint64_t>(kDefaultMemoryShare * double(job_memory_bytes()));
    SceneReport local;
    return import::run_isolated(
        path, limits,
        [&](SceneReport& child_report) { return load_with_assimp(path, options, &child_report); },
        report ? *report : local);
}

} // namespace rad
