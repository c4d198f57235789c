// Third-party importers run where their failure cannot take the tool with it (internal
// header): in a child process with a time limit, an address-space limit and a large stack.
// A crash, a hang or exhaustion there becomes an InputError naming the file and how the
// importer failed (signal, time, memory); the child's own errors come back as they were.
#pragma once
#include "radiosity/scene.hpp"

#include <filesystem>
#include <functional>

namespace rad::import {

Scene run_isolated(const std::filesystem::path& path, const ImportLimits& limits,
                   const std::function<Scene(SceneReport&)>& import, SceneReport& report);

} // namespace rad::import
