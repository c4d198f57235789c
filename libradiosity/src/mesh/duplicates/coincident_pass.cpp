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

// Each kind's line: how loud it is, its verb and what the faces are.
struct KindText {
    Case::Kind kind;
    MeshReport::Kind level;
    const char* verb;
    const char* what;
};
constexpr KindText kKindTexts[] = {
    {Case::kMerged, MeshReport::Kind::Change, "dropped ",
     "lying within a face of the same plane and winding"},
    {Case::kWrongCopy, MeshReport::Kind::Change, "dropped ",
     "drawn again facing the other way whose side sees backs or nothing (the copy facing the "
     "scene is kept)"},
    {Case::kTwins, MeshReport::Kind::Change, "kept ",
     "drawn both ways, both sides facing the scene, as the two sides of a sheet"},
    {Case::kUndecided, MeshReport::Kind::Warning, "",
     "drawn both ways; their rays do not tell which side faces the scene, both are kept "
     "(delete, of each pair, the copy facing away from the room, in the file or the modeller)"},
};

void report_kind(const Scene& scene, const CoincidentReport& found, const KindText& text,
                 MeshReport& report) {
    std::size_t count = 0;
    double area = 0;
    for (const auto& c : found.cases)
        if (c.kind == text.kind) ++count, area += c.area;
    if (!count) return;
    char head[200];
    std::snprintf(head, sizeof head, "%zu face(s) of area %.6g ", count, area);
    report.add(text.level, std::string("coincident: ") + text.verb + head + text.what +
                               case_lines(scene, found, text.kind));
}

} // namespace

std::vector<std::size_t> coincident_pass(Scene& scene, MeshReport& report) {
    const auto found = resolve_coincident_faces(scene);
    for (const auto& text : kKindTexts) report_kind(scene, found, text, report);
    return found.kept;
}

} // namespace rad
