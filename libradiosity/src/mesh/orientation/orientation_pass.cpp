// The orientation pass: --flip, the orientation checks, and --orient fix.
#include "radiosity/build_mesh.hpp"
#include "radiosity/orientation.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>

namespace rad {

namespace {

void report_flips(const std::vector<std::pair<std::string, std::size_t>>& flipped, const char* why,
                  MeshReport& report) {
    for (const auto& [group, count] : flipped)
        report.add(MeshReport::Kind::Fix, "--orient fix flipped " + std::to_string(count) +
                                              " face(s) of group " + group + why);
}

// The vote does not turn faces whose winding agrees with the file's own normals (OBJ vn, glTF
// NORMAL): the file says which way they face.
void keep_faces_agreeing_with_normals(const Scene& scene, std::vector<OrientationFinding>& findings,
                                      MeshReport& report) {
    for (auto& finding : findings) {
        std::vector<std::size_t> flip;
        for (const auto f : finding.to_flip) {
            const auto& p = scene.polygons[f];
            std::vector<radfmt::Vec3> pts;
            for (const auto v : p.vertices) pts.push_back(scene.vertices[v]);
            if (length(p.vn_sum) == 0 || dot(newell_normal(pts), p.vn_sum) <= 0) flip.push_back(f);
        }
        if (flip.size() == finding.to_flip.size()) continue;
        report.add(MeshReport::Kind::Warning,
                   "--orient fix left " + std::to_string(finding.to_flip.size() - flip.size()) +
                       " face(s) of group " + scene.groups[finding.group] +
                       " as they are: their winding agrees with the file's own normals");
        finding.to_flip = std::move(flip);
    }
}

// Each finding's fix is kept only if it leaves the scene's surfaces seeing fewer backs than
// before (a vote can be wrong: a room modelled as a solid, a table turned inside out).
void fix_doing_no_harm(Scene& scene, const std::vector<OrientationFinding>& findings,
                       const char* why, MeshReport& report) {
    double before = seen_backs(scene);
    for (const auto& finding : findings) {
        if (finding.to_flip.empty()) continue;
        Scene trial = scene;
        auto flipped = fix_orientation(trial, {finding});
        double after = seen_backs(trial);
        if (after >= before && !finding.instead.empty()) {
            // The other way round: the rest of the surface turned to agree with these faces.
            OrientationFinding other;
            other.to_flip = finding.instead;
            Scene second = scene;
            auto second_flipped = fix_orientation(second, {other});
            if (const double backs = seen_backs(second); backs < after) {
                trial = std::move(second);
                flipped = std::move(second_flipped);
                after = backs;
            }
        }
        if (after < before) {
            scene = std::move(trial);
            char text[160];
            std::snprintf(text, sizeof text,
                          "%s; the surfaces' rays meet %.1f%% backs, were %.1f%%", why, 100 * after,
                          100 * before);
            before = after;
            report_flips(flipped, text, report);
            continue;
        }
        char text[300];
        std::snprintf(text, sizeof text,
                      "--orient fix left %zu face(s) of group %s as they are: flipped, the "
                      "scene's surfaces would see more backs (%.1f%% of what their rays meet, "
                      "against %.1f%%)",
                      finding.to_flip.size(), scene.groups[finding.group].c_str(), 100 * after,
                      100 * before);
        report.add(MeshReport::Kind::Warning, text);
    }
}

// One emitting material's pieces, as turn_lamps_facing_backs judged them.
struct LampMaterial {
    std::vector<const LampTurn*> turned, doubtful; // doubtful: kept, though much of its
    std::size_t pieces = 0;                        // light meets backs
};
constexpr double kDoubtfulLampShare = 0.25;

// "turned the 2 face(s) of emitter lamp: 80% of the light ... from their other side 5% does"
// (the shares face-weighted over the pieces turned), and which pieces when not all were.
std::string turned_text(const Scene& scene, const std::string& material, const LampMaterial& m) {
    std::size_t faces = 0;
    double before = 0, after = 0;
    for (const auto* t : m.turned)
        faces += t->faces, before += t->backs_before * t->faces, after += t->backs_after * t->faces;
    char text[600];
    std::string which;
    if (m.turned.size() < m.pieces)
        which = " in " + std::to_string(m.turned.size()) + " of its " + std::to_string(m.pieces) +
                " separate pieces (the first at " + face_location(scene, m.turned.front()->line) +
                "; the others face the room)";
    std::snprintf(text, sizeof text,
                  "turned the %zu face(s) of emitter %s%s: %.0f%% of the light from their front "
                  "met the back of surfaces (a lamp facing into its fixture), from their other "
                  "side %.0f%% does (--keep-lamps keeps them as drawn)",
                  faces, material.c_str(), which.c_str(), 100 * before / faces,
                  100 * after / faces);
    return text;
}

// "emitter lamp, 1 of its 2 pieces (the first at scene.obj:12): 40% of the light ..."
std::string doubtful_text(const Scene& scene, const std::string& material, const LampMaterial& m) {
    const auto& first = *m.doubtful.front();
    char text[600];
    std::snprintf(text, sizeof text,
                  "emitter %s, %zu of its %zu piece(s) (the first at %s): %.0f%% of the light "
                  "from their front meets the back of surfaces, from their other side %.0f%% "
                  "would; kept as drawn, too little to tell a lamp facing into its fixture (if "
                  "it does, turn those faces in the file, or --flip %s turns all of %s)",
                  material.c_str(), m.doubtful.size(), m.pieces,
                  face_location(scene, first.line).c_str(), 100 * first.backs_before,
                  100 * first.backs_after, material.c_str(), material.c_str());
    return text;
}

// Lamps drawn facing into their fixture are turned (not those turned by hand with --flip),
// piece by piece; pieces that send much of their light onto backs but not enough to turn
// are named.
void turn_lamps(Scene& scene, const MeshOptions& options, MeshReport& report) {
    if (!options.turn_lamps) return;
    const auto pieces = turn_lamps_facing_backs(scene, options.flip);
    std::map<std::string, LampMaterial> by_material;
    for (const auto& piece : pieces) {
        auto& m = by_material[piece.material];
        ++m.pieces;
        if (piece.turned)
            m.turned.push_back(&piece);
        else if (!piece.kept && piece.backs_before > kDoubtfulLampShare &&
                 piece.backs_after < 0.5 * piece.backs_before)
            m.doubtful.push_back(&piece);
    }
    for (const auto& [material, m] : by_material) {
        if (!m.turned.empty())
            report.add(MeshReport::Kind::Change, turned_text(scene, material, m));
        if (!m.doubtful.empty())
            report.add(MeshReport::Kind::Warning, doubtful_text(scene, material, m));
    }
}

// One warning line per finding, those with the most faces first; without --verbose, at most
// kMaxFindingLines of them and a line that counts the rest (a game map gave hundreds).
constexpr std::size_t kMaxFindingLines = 20;
void report_findings(const std::vector<OrientationFinding>& findings, const Scene& scene,
                     const MeshOptions& options, MeshReport& report,
                     const std::function<std::string(const OrientationFinding&)>& advice) {
    std::vector<const OrientationFinding*> order;
    for (const auto& f : findings) order.push_back(&f);
    std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
        return a->polygons.size() > b->polygons.size();
    });
    const std::size_t shown =
        options.verbose ? order.size() : std::min(order.size(), kMaxFindingLines);
    for (std::size_t k = 0; k < shown; ++k)
        report.add(MeshReport::Kind::Warning, describe(*order[k], scene) + advice(*order[k]));
    if (shown == order.size()) return;
    std::size_t faces = 0;
    for (std::size_t k = shown; k < order.size(); ++k) faces += order[k]->polygons.size();
    report.add(MeshReport::Kind::Warning, "and " + std::to_string(order.size() - shown) +
                                              " more such finding(s), " + std::to_string(faces) +
                                              " face(s) in all, none larger than those above " +
                                              "(rad-mesh -v lists every one)");
}

} // namespace

std::vector<bool> orientation_pass(Scene& scene, const MeshOptions& options, MeshReport& report) {
    using Kind = MeshReport::Kind;
    for (const auto& flipped : flip_groups(scene, options.flip))
        report.add(Kind::Note,
                   "--flip " + flipped.name + " reversed " + std::to_string(flipped.faces) +
                       " face(s) of the " + flipped.what +
                       (flipped.what == "connected surface" ? " of that face" : " of that name"));
    const auto findings = check_orientation(scene);
    report_findings(findings, scene, options, report, [&](const OrientationFinding& finding) {
        if (options.orient_fix || finding.to_flip.empty()) return std::string();
        if (!finding.material)
            return std::string("; --orient fix would flip them, or --flip the group");
        // In a file without groups, the surface is named by a face of it.
        if (finding.kind == OrientationFinding::Kind::AgainstNeighbours)
            return std::string("; --orient fix would flip them");
        return "; --orient fix would flip them, or --flip " +
               face_location(scene, finding.surface_line) + " that surface alone";
    });
    turn_lamps(scene, options, report);
    std::vector<bool> turned(scene.polygons.size(), false);
    if (options.orient_fix) {
        fix_doing_no_harm(scene, findings, "", report);
        // With closed objects facing outward, rays tell which way open surfaces face.
        auto facing = check_facing_by_visibility(scene);
        report_findings(facing, scene, options, report,
                        [](const OrientationFinding&) { return std::string(); });
        keep_faces_agreeing_with_normals(scene, facing, report);
        fix_doing_no_harm(scene, facing, " (visibility)", report);
        return turned;
    }
    // Only the findings that are safe to act on: a closed room facing out, and faces wound
    // against the rest of their surface ("inside out" can be a room that does not enclose
    // everything: a beam sticking out through its wall).
    using Finding = OrientationFinding::Kind;
    for (const auto& finding : findings)
        if (finding.kind == Finding::RoomOutward || finding.kind == Finding::AgainstNeighbours)
            for (const auto f : finding.to_flip) turned[f] = !turned[f];
    return turned;
}

} // namespace rad
