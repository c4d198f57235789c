// The rules that tie files of the chain together: what a derived file records about the
// files it was made from, and the check that a file belongs to a mesh.
#pragma once
#include "radfmt/kinds.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace radfmt {

// The command line as recorded in provenance headers. Options that cannot change a result
// (--threads N, -q/--quiet) are left out, so outputs are byte-identical at any thread count.
std::string command_line(int argc, const char* const* argv);

// A file a new file is made from: a file of the chain (with its header, already read) or a
// plain source file such as an OBJ (header null: it is hashed from disk).
struct Parent {
    std::filesystem::path path;
    const Header* header = nullptr;
};

// The header of a file made by `tool` running `command` from `parents`: an input record
// (path and content hash) per parent, and as provenance the history of the parent with the
// longest one (the last such parent on a tie), so the chain reads oldest step first.
Header derived_header(std::string tool, std::string command, std::span<const Parent> parents);

// Refuses `file` (a form-factor or radiosity file, recording the geometry it was computed
// for in its `mesh_geometry_hash` field, with `file_patches` rows) unless it belongs to the
// mesh at `mesh_path`. `remedy` tells the user what to run again. Returns the mesh's
// geometry hash (which the file records), so callers need not hash the mesh again.
std::string require_same_geometry(const std::filesystem::path& file, const Header& header,
                                  std::uint64_t file_patches,
                                  const std::filesystem::path& mesh_path, const MeshData& mesh,
                                  std::string_view remedy);

// The file a solution was solved with (rad-solve --direct: a .lum or a .sky): `given` when not
// empty, else the path its header records (`direct`), or, when that file is gone and one of
// its name lies beside the solution, that one (the pair moved together). Empty when neither
// is given nor recorded.
std::string solution_direct_path(const Header& solution_header,
                                 const std::filesystem::path& solution_path,
                                 const std::string& given);

// Whether the file the solution records as its `direct` input has changed since: its recorded
// content hash is not `file_hash` (false when the solution records none).
bool solution_direct_changed(const Header& solution_header, const std::string& file_hash);

} // namespace radfmt
