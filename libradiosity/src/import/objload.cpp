// Reading OBJ + MTL as people export them: tinyobjloader parses, a line-by-line check names
// the file and line of what is malformed, and what can be repaired (a missing material, a
// material library elsewhere, whitespace, textures) is repaired and reported.
#include "import/precheck.hpp"
#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/specular_materials.hpp"
#include "radiosity/stages.hpp"
#include "radiosity/text_input.hpp"
#include "radiosity/texture.hpp"
#include "radiosity/vec.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

namespace rad {
namespace fs = std::filesystem;

namespace {

std::string trim(std::string text) {
    const auto end = text.find_last_not_of(" \t\r\n");
    text.erase(end == std::string::npos ? 0 : end + 1);
    const auto begin = text.find_first_not_of(" \t");
    return begin == std::string::npos ? std::string() : text.substr(begin);
}

// The file names of an `mtllib` line: separated by spaces or tabs, "\ " escapes a space.
std::vector<std::string> library_names(const std::string& rest) {
    std::vector<std::string> names;
    std::string name;
    bool escaped = false;
    for (const char c : rest) {
        if (escaped) {
            name += c;
            escaped = false;
        } else if (c == '\\') {
            escaped = true;
        } else if (c == ' ' || c == '\t' || c == '\r') {
            if (!name.empty()) names.push_back(std::move(name));
            name.clear();
        } else {
            name += c;
        }
    }
    if (!name.empty()) names.push_back(std::move(name));
    return names;
}

struct Library {
    int line;
    std::string name;
    fs::path found;                  // empty when not found
    std::vector<std::string> looked; // where it was looked for
};

struct LintResult {
    std::vector<int> face_lines;
    // Each face's corners: tinyobjloader keeps a face's count in a byte, so a face of 500
    // corners reads as 244 and every face after it starts in the wrong place.
    std::vector<int> face_corners;
    std::vector<std::pair<int, std::string>> usemtl; // line, material name as tinyobj reads it
    std::vector<int> faces_without_material;         // before any usemtl
    std::vector<Library> libraries;
    std::size_t vertex_count = 0;
    std::size_t texcoord_count = 0, normal_count = 0; // vt and vn lines so far
    // Face corners naming a vt or vn that does not exist (ignored: neither shapes a patch).
    std::size_t dangling_corners = 0;
    std::string first_dangling; // "line 62: '5/1/1' refers to normal (vn) 1 of 0"
};

// Looks for a material library next to the OBJ, in the current directory, then in the
// --mtl-path folders (a name with folders also by its file name alone, next to the OBJ and in
// those folders); an absolute name only where it says.
Library find_library(const fs::path& obj, int line, const std::string& name,
                     const SceneOptions& options) {
    // The scene's folder is the boundary: a name that leaves it (absolute, or climbing out
    // with '..') is refused, unless allowed.
    if (!options.allow_outside_refs)
        import::referenced_file(FileLoc{obj.string(), line}.str(), obj.parent_path(), name,
                                "mtllib", false);
    Library lib{line, name, {}, {}};
    std::vector<fs::path> candidates;
    if (fs::path(name).is_absolute()) {
        candidates.push_back(name);
    } else {
        candidates.push_back(obj.parent_path() / name);
        candidates.push_back(fs::current_path() / name);
        for (const auto& dir : options.mtl_paths) candidates.push_back(dir / name);
        // A library named with folders of another tree (sub/dir/x.mtl) is also looked for by
        // its file name, next to the OBJ and in each --mtl-path folder.
        if (fs::path(name).has_parent_path()) {
            const auto file = fs::path(name).filename();
            candidates.push_back(obj.parent_path() / file);
            for (const auto& dir : options.mtl_paths) candidates.push_back(dir / file);
        }
    }
    for (const auto& candidate : candidates) {
        lib.looked.push_back(candidate.lexically_normal().string());
        if (fs::is_regular_file(candidate)) {
            lib.found = candidate;
            break;
        }
    }
    return lib;
}

// The texture and normal indices of a face corner "v/vt/vn", "v//vn" or "v/vt": each given
// one an integer naming a vt or vn line defined before (negative: counted back).
void check_attribute_references(const std::string& token, std::size_t slash, LintResult& result,
                                const FileLoc& where, bool strict) {
    const auto second = token.find('/', slash + 1);
    const std::string parts[2] = {token.substr(slash + 1, second == std::string::npos
                                                              ? std::string::npos
                                                              : second - slash - 1),
                                  second == std::string::npos ? "" : token.substr(second + 1)};
    const std::size_t counts[2] = {result.texcoord_count, result.normal_count};
    const char* names[2] = {"texture coordinate (vt)", "normal (vn)"};
    for (int k = 0; k < 2; ++k) {
        if (parts[k].empty()) continue;
        long index = 0;
        auto [ptr, ec] = std::from_chars(parts[k].data(), parts[k].data() + parts[k].size(), index);
        if (ec != std::errc() || ptr != parts[k].data() + parts[k].size())
            throw InputError(where, "bad vertex reference '" + token + "'");
        const long count = static_cast<long>(counts[k]);
        const long resolved = index < 0 ? count + index + 1 : index;
        if (index != 0 && resolved >= 1 && resolved <= count) continue;
        const std::string what = "'" + token + "' refers to " + names[k] + " " +
                                 std::to_string(index) + ", but only " + std::to_string(count) +
                                 " are defined";
        if (strict) throw InputError(where, "face corner " + what);
        if (result.dangling_corners++ == 0)
            result.first_dangling = "line " + std::to_string(where.line) + ": " + what;
        return;
    }
}

// Checks what tinyobjloader would accept silently or report without a line number.
// A material library named on line `line`: found, or (with --strict) refused.
Library find_checked_library(const fs::path& obj, int line, const std::string& name,
                             const SceneOptions& options) {
    auto lib = find_library(obj, line, name, options);
    if (lib.found.empty() && options.strict) {
        std::string looked;
        for (const auto& l : lib.looked) looked += (looked.empty() ? "" : ", ") + l;
        throw InputError(FileLoc{obj.string(), line}, "material library '" + name +
                                                          "' not found (looked for " + looked +
                                                          "; --mtl-path DIR adds a folder)");
    }
    return lib;
}

// The words of a line, split at whitespace as `>>` splits them, without a stream.
class Words {
  public:
    explicit Words(std::string_view line) : line_(line) {}
    bool next(std::string_view& word) {
        while (at_ < line_.size() && is_space(line_[at_])) ++at_;
        if (at_ == line_.size()) return false;
        const auto begin = at_;
        while (at_ < line_.size() && !is_space(line_[at_])) ++at_;
        word = line_.substr(begin, at_ - begin);
        return true;
    }
    std::string_view rest() const { return line_.substr(at_); }

  private:
    static bool is_space(char c) {
        return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
    }
    std::string_view line_;
    std::size_t at_ = 0;
};

// A `v` line after its keyword: x y z, then at most a weight or an r g b colour.
void lint_vertex(Words& words, const FileLoc& where) {
    double xyz[3];
    for (int k = 0; k < 3; ++k) {
        std::string_view token;
        if (!words.next(token)) throw InputError(where, "vertex needs three numbers");
        if (spells_non_finite(token))
            throw InputError(where, "vertex coordinate '" + std::string(token) +
                                        "' is not a finite number");
        if (!parse_number(token, xyz[k]))
            throw InputError(where, "vertex coordinate '" + std::string(token) +
                                        "' is not a decimal number within double range (such "
                                        "as 1.5 or -2e-3)");
    }
    // What may follow: a weight w, or an r g b vertex colour (a common extension); numbers,
    // in the same grammar, and nothing else.
    std::string_view extra;
    for (int k = 0; words.next(extra) && extra[0] != '#'; ++k) {
        double ignored = 0;
        if (k >= 3 || !parse_number(extra, ignored))
            throw InputError(where, "unexpected '" + std::string(extra) +
                                        "' after the vertex's x y z (only a weight or an r g b "
                                        "colour may follow, as decimal numbers)");
    }
}

// An `f` line after its keyword: at least three corners, each naming a vertex (and any vt or
// vn) defined before it.
// Checks a face's corners; returns how many it has.
int lint_face(Words& words, const FileLoc& where, bool strict, LintResult& result) {
    std::string_view token;
    int corners = 0;
    while (words.next(token)) {
        long index = 0;
        const auto slash = token.find('/');
        const auto head = token.substr(0, slash);
        auto [ptr, ec] = std::from_chars(head.data(), head.data() + head.size(), index);
        if (ec != std::errc() || ptr != head.data() + head.size())
            throw InputError(where, "bad vertex reference '" + std::string(token) + "'");
        const long count = static_cast<long>(result.vertex_count);
        const long resolved = index < 0 ? count + index + 1 : index;
        if (index == 0 || resolved < 1 || resolved > count)
            throw InputError(where, "face refers to vertex " + std::to_string(index) +
                                        ", but only " + std::to_string(count) +
                                        " vertices are defined");
        if (slash != std::string_view::npos)
            check_attribute_references(std::string(token), slash, result, where, strict);
        ++corners;
    }
    if (corners < 3)
        throw InputError(where, "face has " + std::to_string(corners) +
                                    " vertices; at least 3 are needed");
    return corners;
}

LintResult lint_obj(const fs::path& path, const SceneOptions& options) {
    // A failed read, a NUL byte or a line over 64 MiB is an error naming the line, never an end.
    LineReader in(path.string(), "", kMaxSceneLineBytes);
    LintResult result;
    std::string line;
    int number = 0;
    bool have_material = false;
    const double file_bytes = std::max<double>(1, static_cast<double>(fs::file_size(path)));
    double bytes_read = 0;
    FileLoc where{path.string(), 0}; // the line's, for messages
    while (in.next(line)) {
        where.line = ++number;
        bytes_read += static_cast<double>(line.size() + 1);
        if (number % 65536 == 0) stage_fraction(options.stages, bytes_read / file_bytes);
        if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3); // UTF-8 BOM
        while (!line.empty() && (line.back() == '\r' || line.back() == '\\')) line.pop_back();
        Words words(line);
        std::string_view keyword;
        if (!words.next(keyword) || keyword[0] == '#') continue;
        if (keyword == "v") {
            lint_vertex(words, where);
            ++result.vertex_count;
        } else if (keyword == "vt") {
            ++result.texcoord_count;
        } else if (keyword == "vn") {
            ++result.normal_count;
        } else if (keyword == "f") {
            result.face_corners.push_back(lint_face(words, where, options.strict, result));
            if (!have_material) {
                if (options.strict)
                    throw InputError(where, "face has no material (put 'usemtl NAME' before it, "
                                            "or leave out --strict to give it a default material)");
                result.faces_without_material.push_back(number);
            }
            result.face_lines.push_back(number);
        } else if (keyword == "usemtl") {
            // As tinyobjloader reads it: the first word, whatever whitespace surrounds it.
            std::string_view name;
            words.next(name);
            result.usemtl.emplace_back(number, std::string(name));
            have_material = true;
        } else if (keyword == "mtllib") {
            for (const auto& name : library_names(std::string(words.rest())))
                result.libraries.push_back(find_checked_library(path, number, name, options));
        }
    }
    return result;
}

// One MTL file as exporters write it, made safe for tinyobjloader: "newmtl  name  " with
// repeated or trailing whitespace names "name"; colours (Ka, Kd, Ks, Ke, Tf) are checked with
// the chain's number grammar (tinyobjloader reads "abc" or "nan" as 0, and a light silently
// goes out) and a single value means grey ("Kd 0.9" is 0.9 0.9 0.9, the MTL convention, not
// 0.9 0 0). Also notes which lines each material has (Kd, Ns, Tf, Ni, d, Tr): a value left
// out is tinyobjloader's default, no evidence of anything.
std::string normalised_mtl(const fs::path& path,
                           std::map<std::string, std::set<std::string>>& stated) {
    LineReader in(path.string(), "", kMaxSceneLineBytes);
    std::ostringstream out;
    std::string line, current;
    int number = 0;
    while (in.next(line)) {
        ++number;
        if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3); // UTF-8 BOM
        const auto text = trim(line);
        std::istringstream words(text);
        std::string keyword;
        words >> keyword;
        if (keyword == "newmtl") {
            std::string rest;
            std::getline(words, rest);
            current = trim(rest);
            out << "newmtl " << current << '\n';
            continue;
        }
        if (keyword == "Ns" || keyword == "Ni" || keyword == "d" || keyword == "Tr")
            stated[current].insert(keyword);
        if (keyword == "Ka" || keyword == "Kd" || keyword == "Ks" || keyword == "Ke" ||
            keyword == "Tf") {
            std::vector<double> values;
            for (std::string token; words >> token;) {
                if (token[0] == '#') break; // a comment after the values
                double value = 0;
                if (spells_non_finite(token) || !parse_number(token, value))
                    throw InputError(FileLoc{path.string(), number},
                                     keyword + " value '" + token +
                                         "' is not a finite decimal number (spectral and xyz "
                                         "colours are not read)");
                if (value < 0)
                    throw InputError(FileLoc{path.string(), number},
                                     keyword + " value " + token + " is negative");
                values.push_back(value);
            }
            if (values.size() != 1 && values.size() != 3)
                throw InputError(FileLoc{path.string(), number},
                                 keyword + " needs 1 value (grey) or 3 (r g b), not " +
                                     std::to_string(values.size()));
            if (values.size() == 1) values.assign(3, values[0]);
            stated[current].insert(keyword);
            char rgb[128];
            std::snprintf(rgb, sizeof rgb, " %.17g %.17g %.17g", values[0], values[1], values[2]);
            out << keyword << rgb << '\n';
            continue;
        }
        out << text << '\n';
    }
    return out.str();
}

// Hands tinyobjloader the materials of every library, read once before it starts: it
// would otherwise stop at the first file of an `mtllib` line and search only one folder.
class PreloadedMaterials : public tinyobj::MaterialReader {
  public:
    PreloadedMaterials(const std::vector<tinyobj::material_t>& materials,
                       const std::map<std::string, int>& index)
        : materials_(materials), index_(index) {}
    bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* index, std::string*, std::string*) override {
        if (!given_) {
            *materials = materials_;
            *index = index_;
            given_ = true;
        }
        return true;
    }

  private:
    const std::vector<tinyobj::material_t>& materials_;
    const std::map<std::string, int>& index_;
    bool given_ = false;
};

std::string rgb_text(const radfmt::Rgb& c) {
    char text[96];
    std::snprintf(text, sizeof text, "%.4g %.4g %.4g", c[0], c[1], c[2]);
    return text;
}

// The material libraries the OBJ names, each read once, in order.
struct MaterialLibraries {
    std::vector<tinyobj::material_t> materials;
    std::map<std::string, int> index;
    std::vector<fs::path> folder, library; // per material: textures are named relative to it
    // Per material, the keywords of the lines its library gives (Kd, Ns, Tf, Ni, d, Tr).
    std::map<std::string, std::set<std::string>> stated;
    bool states(const std::string& material, const char* keyword) const {
        const auto it = stated.find(material);
        return it != stated.end() && it->second.count(keyword);
    }
};

MaterialLibraries read_material_libraries(const fs::path& path, const LintResult& lint,
                                          Scene& scene, SceneReport& report) {
    MaterialLibraries libs;
    std::set<fs::path> loaded;
    for (const auto& lib : lint.libraries) {
        if (lib.found.empty()) {
            std::string looked;
            for (const auto& l : lib.looked) looked += (looked.empty() ? "" : ", ") + l;
            report.missing_libraries.push_back("'" + lib.name + "' (line " +
                                               std::to_string(lib.line) +
                                               ") not found; looked for " + looked);
            continue;
        }
        if (fs::path(lib.name).has_parent_path() &&
            lib.found.filename() == fs::path(lib.name).filename() &&
            fs::weakly_canonical(lib.found) != fs::weakly_canonical(path.parent_path() / lib.name))
            report.libraries_found_by_name.push_back("'" + lib.name + "' (line " +
                                                     std::to_string(lib.line) + ") as " +
                                                     lib.found.lexically_normal().string());
        const auto canonical = fs::weakly_canonical(lib.found);
        if (!loaded.insert(canonical).second) continue;
        std::istringstream text(normalised_mtl(lib.found, libs.stated));
        std::string warn, err;
        tinyobj::LoadMtl(&libs.index, &libs.materials, &text, &warn, &err);
        libs.folder.resize(libs.materials.size(), lib.found.parent_path());
        libs.library.resize(libs.materials.size(), lib.found);
        scene.material_files.push_back(lib.found.string());
    }
    return libs;
}

struct ParsedObj {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
};

// tinyobjloader over the OBJ's text, given the materials already read.
ParsedObj parse_obj(const fs::path& path, const MaterialLibraries& libs) {
    ParsedObj parsed;
    std::vector<tinyobj::material_t> used_materials;
    std::string warn, err;
    // The OBJ as text, without a UTF-8 byte-order mark (which would hide the first line's
    // keyword from tinyobjloader, drop a vertex and shift every index after it).
    std::ifstream file(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
    std::istringstream obj(std::move(text));
    PreloadedMaterials reader(libs.materials, libs.index);
    if (!tinyobj::LoadObj(&parsed.attrib, &parsed.shapes, &used_materials, &warn, &err, &obj,
                          &reader, /*triangulate=*/false, /*default_vcols_fallback=*/false))
        throw InputError(path.string() + ": " + err);
    return parsed;
}

// A map_Kd texture's mean colour as the material's reflectance (times Kd when the library
// gives one that is not black); a missing or unreadable texture is reported.
void apply_texture(const tinyobj::material_t& m, std::size_t index, const MaterialLibraries& libs,
                   const SceneOptions& options, radfmt::Material& material, MaterialSource& source,
                   Scene& scene, SceneReport& report) {
    const auto texture =
        import::referenced_file(libs.library[index], libs.folder[index], m.diffuse_texname,
                                "material '" + m.name + "' map_Kd", options.allow_outside_refs);
    std::string problem;
    if (!fs::is_regular_file(texture)) {
        report.texture_problems.push_back(material.name + ": texture " + texture.string() +
                                          " not found");
        source.texture_missing = true;
    } else if (const auto mean =
                   mean_texture_colour(texture, problem, options.max_texture_pixels)) {
        const bool kd_black = !libs.states(m.name, "Kd") ||
                              (m.diffuse[0] == 0 && m.diffuse[1] == 0 && m.diffuse[2] == 0);
        for (int k = 0; k < 3; ++k)
            material.reflectance[k] = kd_black ? (*mean)[k] : (*mean)[k] * m.diffuse[k];
        report.textures_averaged.push_back(material.name + ": " + texture.string() + ", mean " +
                                           rgb_text(*mean));
        if (kd_black) report.textures_replacing_kd.push_back(material.name);
        if (std::find(scene.material_files.begin(), scene.material_files.end(), texture.string()) ==
            scene.material_files.end())
            scene.material_files.push_back(texture.string());
    } else {
        report.texture_problems.push_back(material.name + ": texture " + texture.string() +
                                          " unreadable (" + problem + ")");
        source.texture_missing = true;
    }
}

// The libraries' materials as the scene's, in their order (Kd, Ke; what else the MTL says is
// kept for the material checks).
void add_materials(const fs::path& path, const MaterialLibraries& libs, const SceneOptions& options,
                   Scene& scene, SceneReport& report) {
    for (std::size_t index = 0; index < libs.materials.size(); ++index) {
        const auto& m = libs.materials[index];
        radfmt::Material material;
        material.name = m.name;
        MaterialSource source;
        source.illum = m.illum;
        for (int k = 0; k < 3; ++k) {
            material.reflectance[k] = m.diffuse[k];
            material.emission[k] = m.emission[k];
            source.ambient[k] = m.ambient[k];
            source.specular[k] = m.specular[k];
            source.transmittance[k] = m.transmittance[k];
        }
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(material.reflectance[k]) || material.reflectance[k] < 0 ||
                !std::isfinite(material.emission[k]) || material.emission[k] < 0)
                throw InputError(path.string() + ": material '" + m.name +
                                 "' has a negative or non-finite Kd or Ke");
        }
        if (!m.diffuse_texname.empty())
            apply_texture(m, index, libs, options, material, source, scene, report);
        MtlSpecularInput mtl;
        mtl.name = m.name;
        mtl.illum = m.illum;
        mtl.diffuse = material.reflectance;
        mtl.specular = source.specular;
        mtl.filter = source.transmittance;
        mtl.ior = m.ior;
        mtl.dissolve = m.dissolve;
        if (libs.states(m.name, "Ns")) mtl.shininess = m.shininess;
        mtl.states_filter = libs.states(m.name, "Tf");
        mtl.states_ior = libs.states(m.name, "Ni");
        mtl.states_dissolve = libs.states(m.name, "d") || libs.states(m.name, "Tr");
        const auto reading = read_mtl_material(mtl);
        material.specular = reading.specular;
        material.reflectance = reading.diffuse;
        if (!reading.why.empty())
            (reading.changed ? report.materials_changed : report.materials_read)
                .push_back("material '" + m.name + "': " + reading.why);
        scene.materials.push_back(material);
        scene.material_sources.push_back(source);
    }
}

// The material of a face whose material no library defines: its `usemtl` name with the
// default reflectance (so that rad-solve's --emission NAME= and --reflectance NAME= still find
// it), or one default material for faces before any usemtl, each made when first needed.
class MissingMaterials {
  public:
    MissingMaterials(const fs::path& path, const LintResult& lint, const SceneOptions& options,
                     Scene& scene, SceneReport& report)
        : lint_(lint), options_(options), scene_(scene), report_(report) {
        for (const auto& m : scene.materials) known_.insert(m.name);
        std::set<std::string> reported;
        for (const auto& [line, name] : lint.usemtl)
            if (!known_.count(name) && reported.insert(name).second) {
                if (options.strict)
                    throw InputError(FileLoc{path.string(), line},
                                     "unknown material '" + name + "' (not defined in any mtllib)");
                report.unknown_materials.push_back(name + " (line " + std::to_string(line) + ")");
            }
    }
    // For the face at `line` (0: not known).
    std::uint32_t material_at(int line) {
        const auto name = line > 0 ? usemtl_at(line) : std::string();
        return name.empty() ? default_material() : named_default(name);
    }

  private:
    std::uint32_t default_material() {
        if (report_.default_material.empty()) {
            report_.default_material = "default";
            while (known_.count(report_.default_material)) report_.default_material += "_";
            scene_.materials.push_back(
                {report_.default_material, options_.default_reflectance, {}, {}});
            scene_.material_sources.push_back({});
        }
        return static_cast<std::uint32_t>(
            std::find_if(scene_.materials.begin(), scene_.materials.end(),
                         [&](const auto& m) { return m.name == report_.default_material; }) -
            scene_.materials.begin());
    }
    std::uint32_t named_default(const std::string& name) {
        const auto it = named_.find(name);
        if (it != named_.end()) return it->second;
        const auto id = static_cast<std::uint32_t>(scene_.materials.size());
        scene_.materials.push_back({name, options_.default_reflectance, {}, {}});
        scene_.material_sources.push_back({});
        named_[name] = id;
        return id;
    }
    // The name of the last `usemtl` before `line` that no library defines ("" if none).
    std::string usemtl_at(int line) const {
        std::string name;
        for (const auto& [at, used] : lint_.usemtl) {
            if (at > line) break;
            name = used;
        }
        return known_.count(name) ? std::string() : name;
    }

    const LintResult& lint_;
    const SceneOptions& options_;
    Scene& scene_;
    SceneReport& report_;
    std::set<std::string> known_;
    std::map<std::string, std::uint32_t> named_;
};

// One face's corners, and the sum of its vn normals when every corner has one.
Polygon polygon_of(const tinyobj::shape_t& shape, std::size_t offset, int count,
                   const tinyobj::attrib_t& attrib) {
    Polygon poly;
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
    return poly;
}

// A face's corner count: the lint's, as tinyobjloader keeps only its low byte (the two are
// checked to agree there). Without the lint's faces matched one to one, a face of more than
// 255 corners cannot be read.
int face_corners(const fs::path& path, const LintResult& lint, bool lines_match,
                 std::size_t face_number, unsigned char parsed) {
    if (!lines_match) {
        for (std::size_t k = 0; k < lint.face_corners.size(); ++k)
            if (lint.face_corners[k] > 255)
                throw InputError(FileLoc{path.string(), lint.face_lines[k]},
                                 "face of " + std::to_string(lint.face_corners[k]) +
                                     " corners: the OBJ reader takes 255 at most here (split "
                                     "the face, or export it triangulated)");
        return parsed;
    }
    const int corners = lint.face_corners[face_number];
    if ((corners & 0xff) != parsed)
        throw InternalError(path.string() + ": face at line " +
                            std::to_string(lint.face_lines[face_number]) + " has " +
                            std::to_string(corners) + " corners, the OBJ reader saw " +
                            std::to_string(parsed));
    return corners;
}

// The shapes' faces as the scene's polygons, with their groups, lines and materials.
void add_polygons(const fs::path& path, const ParsedObj& parsed, const LintResult& lint,
                  std::size_t library_materials, const SceneOptions& options, Scene& scene,
                  SceneReport& report) {
    MissingMaterials missing(path, lint, options, scene, report);
    std::size_t faces = 0;
    for (const auto& s : parsed.shapes) faces += s.mesh.num_face_vertices.size();
    const bool lines_match = faces == lint.face_lines.size();
    std::size_t face_number = 0;
    for (const auto& shape : parsed.shapes) {
        const std::string group_name = shape.name.empty() ? "default" : shape.name;
        std::uint32_t group = 0;
        for (; group < scene.groups.size(); ++group)
            if (scene.groups[group] == group_name) break;
        if (group == scene.groups.size()) scene.groups.push_back(group_name);
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face_number) {
            const int count =
                face_corners(path, lint, lines_match, face_number, shape.mesh.num_face_vertices[f]);
            Polygon poly = polygon_of(shape, offset, count, parsed.attrib);
            offset += count;
            poly.group = group;
            poly.line = lines_match ? lint.face_lines[face_number] : 0;
            const int material = shape.mesh.material_ids[f];
            if (material < 0 || material >= static_cast<int>(library_materials)) {
                if (options.strict)
                    throw InputError(FileLoc{path.string(), poly.line},
                                     "face has no known material");
                poly.material = missing.material_at(lines_match ? poly.line : 0);
                if (report.faces_defaulted++ == 0) report.first_defaulted_line = poly.line;
            } else {
                poly.material = static_cast<std::uint32_t>(material);
            }
            scene.polygons.push_back(std::move(poly));
        }
    }
}

} // namespace

Scene load_obj(const fs::path& path, const SceneOptions& options, SceneReport* report_out) {
    if (!fs::is_regular_file(path)) throw InputError(path.string() + ": no such OBJ file");
    SceneReport local_report;
    SceneReport& report = report_out ? *report_out : local_report;
    const auto lint = lint_obj(path, options);
    report.dangling_corners = lint.dangling_corners;
    report.first_dangling = lint.first_dangling;

    Scene scene;
    scene.path = path.string();
    const auto libs = read_material_libraries(path, lint, scene, report);
    begin_stage(options.stages, "parsing " + path.filename().string());
    const auto parsed = parse_obj(path, libs);
    for (std::size_t i = 0; i + 2 < parsed.attrib.vertices.size(); i += 3)
        scene.vertices.push_back({parsed.attrib.vertices[i], parsed.attrib.vertices[i + 1],
                                  parsed.attrib.vertices[i + 2]});
    add_materials(path, libs, options, scene, report);
    add_polygons(path, parsed, lint, libs.materials.size(), options, scene, report);
    if (scene.polygons.empty()) throw InputError(path.string() + ": scene is empty (no faces)");
    return scene;
}

} // namespace rad
