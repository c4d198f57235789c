// Cheap checks of our own before a third-party importer sees a file (internal header): what
// would hang it, crash it, or have it read outside the scene or read wrong values quietly.
#pragma once
#include "radiosity/scene.hpp"

#include <filesystem>
#include <string>

namespace rad::import {

// A file's extension in lower case (".glb"): how readers are chosen.
std::string lower_extension(const std::filesystem::path& path);

// A file the scene refers to (`reference`, as written in `from`) resolved against `folder`:
// refused when absolute or outside `folder` (unless `allow_outside`), or when it names
// something other than a regular file (a FIFO or device is never opened). Returns the path.
std::filesystem::path referenced_file(const std::filesystem::path& from,
                                      const std::filesystem::path& folder,
                                      const std::string& reference, const std::string& what,
                                      bool allow_outside);

// The scene file itself is a regular file; a PLY's header is complete; a glTF's nodes form a
// tree of bounded depth, its accessors, views and buffers agree in range, and the files it
// names are inside its folder. Throws InputError naming the file and the element.
void check_before_import(const std::filesystem::path& path, const SceneOptions& options);

// Deeper node hierarchies than this are refused (importers recurse once per level).
inline constexpr std::size_t kMaxNodeDepth = 1000;

} // namespace rad::import
