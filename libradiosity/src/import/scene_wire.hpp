// A Scene and its SceneReport as bytes and back (internal header): how an import run in a
// child process hands its result to the tool.
#pragma once
#include "radiosity/scene.hpp"

#include <string>
#include <string_view>

namespace rad::import {

std::string encode_scene(const Scene& scene, const SceneReport& report);
// Throws InternalError when `bytes` is not what encode_scene wrote.
void decode_scene(std::string_view bytes, Scene& scene, SceneReport& report);

} // namespace rad::import
