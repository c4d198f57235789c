#include "radfmt/chain.hpp"

#include <algorithm>

namespace radfmt {
namespace fs = std::filesystem;

std::string command_line(int argc, const char* const* argv) {
    std::string out;
    for (int i = 0; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--threads") {
            ++i;
            continue;
        }
        if (arg.rfind("--threads=", 0) == 0 || arg == "-q" || arg == "--quiet") continue;
        if (i == 0) arg = fs::path(arg).filename().string();
        const bool plain =
            !arg.empty() && arg.find_first_of(" \t\"'\\$`*?;&|<>()") == std::string::npos;
        if (!out.empty()) out += ' ';
        if (plain) {
            out += arg;
        } else {
            out += '\'';
            for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
            out += '\'';
        }
    }
    return out;
}

Header derived_header(std::string tool, std::string command, std::span<const Parent> parents) {
    Header h;
    h.tool = std::move(tool);
    h.command = std::move(command);
    const Header* longest = nullptr;
    for (const auto& parent : parents) {
        if (parent.header) {
            h.inputs.push_back({parent.path.string(), parent.header->file_hash});
            if (!longest || parent.header->provenance.size() >= longest->provenance.size())
                longest = parent.header;
        } else {
            h.inputs.push_back({parent.path.string(), hash_file(parent.path)});
        }
    }
    if (!longest) return h;
    // The longest line of ancestors, then what the other parents add that it lacks (a .lum's
    // rad-ff --luminaires beside a .ff's rad-ff, both from the same mesh), in their order.
    h.provenance = longest->chain();
    for (const auto& parent : parents) {
        if (!parent.header || parent.header == longest) continue;
        for (auto& ancestor : parent.header->chain())
            if (std::find(h.provenance.begin(), h.provenance.end(), ancestor) == h.provenance.end())
                h.provenance.push_back(std::move(ancestor));
    }
    return h;
}

std::string require_same_geometry(const fs::path& file, const Header& header,
                                  std::uint64_t file_patches, const fs::path& mesh_path,
                                  const MeshData& mesh, std::string_view remedy) {
    const auto* recorded = header.find("mesh_geometry_hash");
    const auto actual = mesh.geometry_hash();
    if (recorded && *recorded == actual && file_patches == mesh.patches.size()) return actual;
    throw FormatError(file.string() + " is stale: it does not belong to " + mesh_path.string() +
                      ": it was computed for a mesh with geometry " +
                      (recorded ? *recorded : std::string("(unknown)")) + " and " +
                      std::to_string(file_patches) + " patches, but " + mesh_path.string() +
                      " has " + actual + " and " + std::to_string(mesh.patches.size()) +
                      " patches; " + std::string(remedy));
}

std::string solution_direct_path(const Header& solution_header,
                                 const std::filesystem::path& solution_path,
                                 const std::string& given) {
    if (!given.empty()) return given;
    const auto* recorded = solution_header.find("direct");
    if (!recorded) return "";
    const auto beside = solution_path.parent_path() / fs::path(*recorded).filename();
    if (!fs::exists(*recorded) && fs::exists(beside)) return beside.string();
    return *recorded;
}

bool solution_direct_changed(const Header& solution_header, const std::string& file_hash) {
    const auto* recorded = solution_header.find("direct");
    if (!recorded) return false;
    for (const auto& input : solution_header.inputs)
        if (input.path == *recorded && input.hash != file_hash) return true;
    return false;
}

} // namespace radfmt
