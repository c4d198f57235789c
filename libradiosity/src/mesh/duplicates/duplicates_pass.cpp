// The duplicates pass: faces written twice (same corners, same winding) dropped.
#include "radiosity/build_mesh.hpp"

namespace rad {

void duplicates_pass(Scene& scene, MeshReport& report) {
    const auto duplicates = remove_duplicate_faces(scene);
    if (!duplicates.removed) return;
    std::string lines;
    for (std::size_t k = 0; k < duplicates.lines.size() && k < 10; ++k)
        lines += (k ? ", " : "") + face_number(scene, duplicates.lines[k].first) + " (repeats " +
                 face_number(scene, duplicates.lines[k].second) + ")";
    if (duplicates.lines.size() > 10) lines += ", ...";
    report.add(MeshReport::Kind::Change,
               "deduplicated: dropped " + std::to_string(duplicates.removed) +
                   " duplicate face(s), " + (scene.face_ranges.empty() ? "line " : "") + lines);
}

} // namespace rad
