// Checks before assimp: the scene folder as a boundary, PLY headers, glTF structure.
#include "import/precheck.hpp"

#include "radiosity/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>

namespace rad::import {
namespace fs = std::filesystem;
using nlohmann::json;

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

namespace {
// %XX escapes of a URI decoded (glTF URIs are percent-encoded).
std::string percent_decoded(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uri[i + 1]) &&
            std::isxdigit(uri[i + 2])) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

bool inside(const fs::path& path, const fs::path& folder) {
    const auto p = fs::weakly_canonical(path), f = fs::weakly_canonical(folder);
    auto [end, at] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
    return end == f.end();
}
} // namespace

fs::path referenced_file(const fs::path& from, const fs::path& folder_in,
                         const std::string& reference, const std::string& what,
                         bool allow_outside) {
    const fs::path folder = folder_in.empty() ? fs::path(".") : folder_in;
    const fs::path target(reference);
    const std::string where = from.string() + ": " + what + " '" + reference + "'";
    if (reference.rfind("file:", 0) == 0 || target.is_absolute() || target.has_root_name())
        if (!allow_outside)
            throw InputError(where + " is an absolute path: a scene refers to files in its own "
                                     "folder (--allow-outside-refs allows others)");
    const fs::path resolved = target.is_absolute() ? target : folder / target;
    if (!allow_outside && !inside(resolved, folder))
        throw InputError(where + " lies outside the scene's folder " + folder.string() +
                         " (--allow-outside-refs allows it)");
    std::error_code ec;
    const auto status = fs::status(resolved, ec);
    if (!ec && fs::exists(status) && !fs::is_regular_file(status))
        throw InputError(where + " is not a regular file (a FIFO, device or folder is never "
                                 "opened)");
    return resolved;
}

namespace {
// A PLY's header ends with an end_header line within its first 64 KiB (without it, assimp
// reads on forever).
// The first 64 KiB of a file: where a PLY's header must end.
std::string file_head(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(64 * 1024, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return head;
}

void check_ply_header(const fs::path& path, const std::string& head) {
    if (head.rfind("ply", 0) != 0)
        throw InputError(path.string() + ": not a PLY file (it does not start with 'ply')");
    const auto end = head.find("end_header");
    if (end == std::string::npos || (end > 0 && head[end - 1] != '\n') ||
        (end + 10 < head.size() && head[end + 10] != '\n' && head[end + 10] != '\r'))
        throw InputError(
            path.string() + ": PLY header has no 'end_header' line" +
            (head.size() < 64 * 1024 ? " (a truncated file?)" : " in its first 64 KiB"));
}

// The PLY's vertex positions are finite numbers (assimp drops a vertex of NaN and the faces
// around it change shape quietly). Read when the vertex element comes first and holds only
// scalar properties (fixed-size records): the layout of every PLY exporter we know.
struct PlyLayout {
    std::string format; // ascii, binary_little_endian, binary_big_endian
    std::uint64_t vertices = 0;
    std::vector<std::pair<std::string, std::string>> properties; // (type, name) of a vertex
    std::size_t body = 0;                                        // offset of the data
    bool readable = false;
};

PlyLayout ply_layout(const std::string& head) {
    PlyLayout layout;
    std::istringstream lines(head);
    std::string line;
    bool in_vertex = false, first_element = true, lists = false;
    while (std::getline(lines, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "format") {
            words >> layout.format;
        } else if (keyword == "element") {
            std::string name;
            words >> name;
            in_vertex = first_element && name == "vertex";
            if (in_vertex) words >> layout.vertices;
            first_element = false;
        } else if (keyword == "property" && in_vertex) {
            std::string type, name;
            words >> type >> name;
            if (type == "list") lists = true;
            layout.properties.emplace_back(type, name);
        } else if (keyword == "end_header") {
            layout.body = static_cast<std::size_t>(lines.tellg());
            break;
        }
    }
    layout.readable = layout.vertices > 0 && !lists && layout.body > 0;
    return layout;
}

int ply_size(const std::string& type) {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
        type == "float32")
        return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
}

void check_ply_vertices(const fs::path& path, const std::string& head) {
    const auto layout = ply_layout(head);
    if (!layout.readable) return;
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(layout.body));
    const bool ascii = layout.format == "ascii";
    const bool swap = layout.format == "binary_big_endian";
    std::size_t record = 0;
    for (const auto& [type, name] : layout.properties) {
        if (ply_size(type) == 0) return; // a type we do not know: leave it to assimp
        record += static_cast<std::size_t>(ply_size(type));
    }
    std::string bytes(record, '\0');
    for (std::uint64_t v = 0; v < layout.vertices; ++v) {
        if (!ascii && !in.read(bytes.data(), static_cast<std::streamsize>(record))) return;
        std::size_t at = 0;
        for (const auto& [type, name] : layout.properties) {
            double value = 0;
            if (ascii) {
                std::string token;
                if (!(in >> token)) return;
                if (name != "x" && name != "y" && name != "z") continue;
                if (token.find_first_of("nNiI") != std::string::npos)
                    value = std::numeric_limits<double>::quiet_NaN();
            } else {
                const int size = ply_size(type);
                char raw[8];
                std::memcpy(raw, bytes.data() + at, static_cast<std::size_t>(size));
                at += static_cast<std::size_t>(size);
                if (name != "x" && name != "y" && name != "z") continue;
                if (swap) std::reverse(raw, raw + size);
                if (type == "float" || type == "float32") {
                    float f;
                    std::memcpy(&f, raw, 4);
                    value = f;
                } else if (type == "double" || type == "float64") {
                    std::memcpy(&value, raw, 8);
                }
            }
            if (!std::isfinite(value))
                throw InputError(path.string() + ": vertex " + std::to_string(v) + " has " + name +
                                 " that is not a finite number");
        }
    }
}

// A glTF number that must be a whole number from 0 (indices, offsets, lengths, counts).
std::optional<std::uint64_t> whole(const json& value) {
    if (value.is_number_unsigned()) return value.get<std::uint64_t>();
    if (value.is_number_integer() && value.get<std::int64_t>() >= 0)
        return static_cast<std::uint64_t>(value.get<std::int64_t>());
    return std::nullopt;
}

class GltfCheck {
  public:
    GltfCheck(const fs::path& path, const json& doc, std::uint64_t glb_bin_bytes,
              bool allow_outside)
        : path_(path), doc_(doc), glb_bin_bytes_(glb_bin_bytes), allow_outside_(allow_outside) {}
    void run() {
        check_nodes();
        check_buffers();
        check_views();
        check_accessors();
        check_images();
    }

  private:
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(path_.string() + ": " + what);
    }
    const json& list(const char* name) const {
        static const json empty = json::array();
        if (!doc_.contains(name)) return empty;
        if (!doc_[name].is_array()) fail(std::string("'") + name + "' is not an array");
        return doc_[name];
    }
    // The field `key` of element `i` of `kind` as a whole number below `limit`, if present.
    std::optional<std::uint64_t> field(const json& item, const char* kind, std::size_t i,
                                       const char* key, std::uint64_t limit) const {
        if (!item.is_object())
            fail(std::string(kind) + " " + std::to_string(i) + " is not an object");
        if (!item.contains(key)) return std::nullopt;
        const auto value = whole(item[key]);
        const std::string name = std::string(kind) + " " + std::to_string(i) + ": " + key + " ";
        if (!value) fail(name + item[key].dump() + " is not a whole number from 0");
        if (*value >= limit)
            fail(name + std::to_string(*value) + " is out of range (below " +
                 std::to_string(limit) + ")");
        return value;
    }
    void check_nodes();
    void check_buffers();
    void check_views();
    void check_accessors();
    void check_images();

    const fs::path& path_;
    const json& doc_;
    std::uint64_t glb_bin_bytes_;
    bool allow_outside_;
    std::vector<std::uint64_t> buffer_bytes_, view_bytes_;
};

// Every node has at most one parent, the hierarchy has no cycle, and it is at most
// kMaxNodeDepth deep (walked without recursion).
void GltfCheck::check_nodes() {
    const auto& nodes = list("nodes");
    std::vector<std::vector<std::uint64_t>> children(nodes.size());
    std::vector<int> parents(nodes.size(), 0);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!nodes[i].is_object()) fail("node " + std::to_string(i) + " is not an object");
        if (!nodes[i].contains("children")) continue;
        if (!nodes[i]["children"].is_array())
            fail("node " + std::to_string(i) + ": children is not an array");
        for (const auto& c : nodes[i]["children"]) {
            const auto child = whole(c);
            if (!child || *child >= nodes.size())
                fail("node " + std::to_string(i) + ": child " + c.dump() + " is not a node");
            if (*child == i) fail("node " + std::to_string(i) + " is its own child");
            if (++parents[*child] > 1)
                fail("node " + std::to_string(*child) + " has more than one parent");
            children[i].push_back(*child);
        }
    }
    std::vector<std::size_t> depth(nodes.size(), 0);
    std::vector<std::uint64_t> stack;
    std::size_t reached = 0;
    for (std::size_t root = 0; root < nodes.size(); ++root) {
        if (parents[root] != 0) continue;
        stack.assign(1, root);
        depth[root] = 1;
        while (!stack.empty()) {
            const auto n = stack.back();
            stack.pop_back();
            ++reached;
            if (depth[n] > kMaxNodeDepth)
                fail("the node hierarchy is over " + std::to_string(kMaxNodeDepth) +
                     " levels deep (at node " + std::to_string(n) + ")");
            for (const auto c : children[n]) {
                depth[c] = depth[n] + 1;
                stack.push_back(c);
            }
        }
    }
    // Nodes not reached from a node without a parent sit on a cycle.
    if (reached != nodes.size()) fail("the node hierarchy has a cycle");
}

void GltfCheck::check_buffers() {
    const auto& buffers = list("buffers");
    const fs::path folder = path_.parent_path();
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        const auto bytes = field(buffers[i], "buffer", i, "byteLength", std::uint64_t(1) << 53);
        if (!bytes) fail("buffer " + std::to_string(i) + " has no byteLength");
        buffer_bytes_.push_back(*bytes);
        if (buffers[i].contains("uri")) {
            if (!buffers[i]["uri"].is_string())
                fail("buffer " + std::to_string(i) + ": uri is not a string");
            const auto uri = buffers[i]["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;
            const auto file =
                referenced_file(path_, folder, percent_decoded(uri),
                                "buffer " + std::to_string(i) + " uri", allow_outside_);
            std::error_code ec;
            const auto size = fs::file_size(file, ec);
            if (!ec && size < *bytes)
                fail("buffer " + std::to_string(i) + " ('" + uri + "') holds " +
                     std::to_string(size) + " bytes, less than its byteLength " +
                     std::to_string(*bytes));
        } else if (i == 0 && *bytes > glb_bin_bytes_) {
            fail("buffer 0 has byteLength " + std::to_string(*bytes) + " but the GLB's BIN " +
                 "chunk holds " + std::to_string(glb_bin_bytes_) + " bytes");
        }
    }
}

void GltfCheck::check_views() {
    const auto& views = list("bufferViews");
    for (std::size_t i = 0; i < views.size(); ++i) {
        const auto buffer = field(views[i], "bufferView", i, "buffer", buffer_bytes_.size());
        if (!buffer) fail("bufferView " + std::to_string(i) + " has no buffer");
        const auto offset = field(views[i], "bufferView", i, "byteOffset", std::uint64_t(1) << 53);
        const auto length = field(views[i], "bufferView", i, "byteLength", std::uint64_t(1) << 53);
        field(views[i], "bufferView", i, "byteStride", 253);
        if (!length) fail("bufferView " + std::to_string(i) + " has no byteLength");
        if (offset.value_or(0) + *length > buffer_bytes_[*buffer])
            fail("bufferView " + std::to_string(i) + " (bytes " +
                 std::to_string(offset.value_or(0)) + " to " +
                 std::to_string(offset.value_or(0) + *length) + ") runs past the end of buffer " +
                 std::to_string(*buffer) + " (" + std::to_string(buffer_bytes_[*buffer]) +
                 " bytes)");
        view_bytes_.push_back(*length);
    }
}

void GltfCheck::check_accessors() {
    static const std::map<std::string, int> components{{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3},
                                                       {"VEC4", 4},   {"MAT2", 4}, {"MAT3", 9},
                                                       {"MAT4", 16}};
    const auto& accessors = list("accessors");
    const auto& views = list("bufferViews");
    for (std::size_t i = 0; i < accessors.size(); ++i) {
        const auto& a = accessors[i];
        const std::string name = "accessor " + std::to_string(i);
        const auto view = field(a, "accessor", i, "bufferView", view_bytes_.size());
        const auto offset = field(a, "accessor", i, "byteOffset", std::uint64_t(1) << 53);
        const auto count = field(a, "accessor", i, "count", std::uint64_t(1) << 32);
        const auto type = field(a, "accessor", i, "componentType", 5127);
        if (!count || *count == 0) fail(name + " has no count (or 0)");
        const int size = type == 5120 || type == 5121   ? 1
                         : type == 5122 || type == 5123 ? 2
                         : type == 5125 || type == 5126 ? 4
                                                        : 0;
        if (size == 0) fail(name + ": componentType is not one glTF defines");
        if (!a.contains("type") || !a["type"].is_string() ||
            !components.count(a["type"].get<std::string>()))
            fail(name + ": type is not one glTF defines");
        if (!view) continue; // all zeros (or sparse only)
        const std::uint64_t element = std::uint64_t(size) * components.at(a["type"]);
        const std::uint64_t stride =
            views[*view].contains("byteStride") ? *whole(views[*view]["byteStride"]) : element;
        const std::uint64_t end = offset.value_or(0) + stride * (*count - 1) + element;
        if (end > view_bytes_[*view])
            fail(name + " (" + std::to_string(*count) + " elements from byte " +
                 std::to_string(offset.value_or(0)) + ") runs past the end of bufferView " +
                 std::to_string(*view) + " (" + std::to_string(view_bytes_[*view]) + " bytes)");
    }
}

void GltfCheck::check_images() {
    const auto& images = list("images");
    for (std::size_t i = 0; i < images.size(); ++i)
        if (images[i].is_object() && images[i].contains("uri") && images[i]["uri"].is_string()) {
            const auto uri = images[i]["uri"].get<std::string>();
            if (uri.rfind("data:", 0) != 0)
                referenced_file(path_, path_.parent_path(), percent_decoded(uri),
                                "image " + std::to_string(i) + " uri", allow_outside_);
        }
}

// The JSON of a .gltf, or of a .glb's first chunk (and the length of its BIN chunk).
json gltf_document(const fs::path& path, std::uint64_t& bin_bytes) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bin_bytes = 0;
    std::string text;
    if (lower_extension(path) == ".glb") {
        auto u32 = [&](std::size_t at) {
            std::uint32_t v = 0;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 ||
            bytes.compare(16, 4, "JSON") != 0)
            throw InputError(path.string() + ": not a GLB file (no glTF header and JSON chunk)");
        const std::uint64_t length = u32(12);
        if (20 + length > bytes.size())
            throw InputError(path.string() + ": the GLB's JSON chunk runs past the file's end");
        text = bytes.substr(20, length);
        const std::uint64_t bin_at = 20 + length;
        if (bin_at + 8 <= bytes.size() &&
            bytes.compare(bin_at + 4, 4, std::string("BIN\0", 4)) == 0)
            bin_bytes = std::min<std::uint64_t>(u32(bin_at), bytes.size() - bin_at - 8);
    } else {
        text = std::move(bytes);
    }
    auto doc = json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object())
        throw InputError(path.string() + ": cannot read the scene (its JSON does not parse)");
    return doc;
}
} // namespace

void check_before_import(const fs::path& path, const SceneOptions& options) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status)) throw InputError(path.string() + ": no such scene file");
    if (!fs::is_regular_file(status))
        throw InputError(path.string() + ": not a regular file (a FIFO, device or folder is "
                                         "never opened)");
    const auto ext = lower_extension(path);
    if (ext == ".ply") {
        const auto head = file_head(path);
        check_ply_header(path, head);
        check_ply_vertices(path, head);
    }
    if (ext == ".gltf" || ext == ".glb") {
        std::uint64_t bin_bytes = 0;
        const auto doc = gltf_document(path, bin_bytes);
        GltfCheck(path, doc, bin_bytes, options.allow_outside_refs).run();
    }
}

} // namespace rad::import
