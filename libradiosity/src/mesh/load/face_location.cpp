// Where a face of the input is, for messages: an OBJ line, or a face of a glTF node's mesh.
#include "radiosity/error.hpp"
#include "radiosity/scene.hpp"

#include <algorithm>

namespace rad {

std::string face_number(const Scene& scene, int line) {
    if (scene.face_ranges.empty() || line <= 0) return std::to_string(line);
    const auto after =
        std::upper_bound(scene.face_ranges.begin(), scene.face_ranges.end(), line,
                         [](int n, const Scene::FaceRange& r) { return n < r.first; });
    if (after == scene.face_ranges.begin()) return "face " + std::to_string(line);
    const auto& range = *(after - 1);
    return "face " + std::to_string(line) + " (" + range.origin + ", its face " +
           std::to_string(line - range.first + 1) + ")";
}

std::string face_location(const Scene& scene, int line) {
    if (scene.face_ranges.empty()) return FileLoc{scene.path, line}.str();
    return scene.path + ": " + face_number(scene, line);
}

} // namespace rad
