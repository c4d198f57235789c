// The coincident-faces pass: faces in one plane that overlap, resolved and reported.
#include "radiosity/build_mesh.hpp"
#include "radiosity/coincident.hpp"

#include <cstdio>

namespace rad {

namespace {

using Case = CoincidentCase;

// "line 12 (copy of 3), ..." for the first cases of a kind (none for formats without lines).
std::string case_lines(const Scene& scene, const CoincidentReport& found, Case::Kind kind) {
    std::string lines;
    std::size_t listed = 0, count = 0;
    for (const auto& c : found.cases) {
        if (c.kind != kind) continue;
        ++count;
        if (listed >= 6 || c.other_line <= 0) continue;
        lines += (listed++ ? ", " : "") + face_number(scene, c.other_line) +
                 (kind == Case::kMerged || kind == Case::kWrongCopy ? " (copy of " : " (twin of ") +
                 face_number(scene, c.kept_line) + ")";
    }
    if (lines.empty()) return "";
    return std::string(scene.face_ranges.empty() ? ", line " : ", ") + lines +
           (count > listed ? ", ..." : "");
}

void report_kind(const Scene& scene, const CoincidentReport& found, Case::Kind kind,
                 MeshReport& report) {
    std::size_t count = 0;
    double area = 0;
    for (const auto& c : found.cases)
        if (c.kind == kind) ++count, area += c.area;
    if (!count) return;
    char head[200];
    std::snprintf(head, sizeof head, "%zu face(s) of area %.6g ", count, area);
    const auto lines = case_lines(scene, found, kind);
    using K = MeshReport::Kind;
    switch (kind) {
    case Case::kMerged:
        report.add(K::Change, std::string("coincident: dropped ") + head +
                                  "lying within a face of the same plane and winding" + lines);
        break;
    case Case::kWrongCopy:
        report.add(K::Change, std::string("coincident: dropped ") + head +
                                  "drawn again facing the other way whose side sees backs or "
                                  "nothing (the copy facing the scene is kept)" +
                                  lines);
        break;
    case Case::kTwins:
        report.add(K::Change, std::string("coincident: kept ") + head +
                                  "drawn both ways, both sides facing the scene, as the two "
                                  "sides of a sheet" +
                                  lines);
        break;
    case Case::kUndecided:
        report.add(K::Warning, std::string("coincident: ") + head +
                                   "drawn both ways; their rays do not tell which side faces the "
                                   "scene, both are kept (--flip GROUP, or delete one copy)" +
                                   lines);
        break;
    }
}

} // namespace

std::vector<std::size_t> coincident_pass(Scene& scene, MeshReport& report) {
    const auto found = resolve_coincident_faces(scene);
    for (const auto kind : {Case::kMerged, Case::kWrongCopy, Case::kTwins, Case::kUndecided})
        report_kind(scene, found, kind, report);
    return found.kept;
}

} // namespace rad
