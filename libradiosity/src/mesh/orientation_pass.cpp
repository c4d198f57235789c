// The orientation pass: --flip, the orientation checks, and --orient fix.
#include "radiosity/build_mesh.hpp"
#include "radiosity/orientation.hpp"

namespace rad {

namespace {

void report_flips(const std::vector<std::pair<std::string, std::size_t>>& flipped, const char* why,
                  MeshReport& report) {
    for (const auto& [group, count] : flipped)
        report.add(MeshReport::Kind::Fix, "--orient fix flipped " + std::to_string(count) +
                                              " face(s) of group " + group + why);
}

} // namespace

std::vector<bool> orientation_pass(Scene& scene, const MeshOptions& options, MeshReport& report) {
    using Kind = MeshReport::Kind;
    if (!options.flip.empty())
        report.add(Kind::Note, "--flip reversed " +
                                   std::to_string(flip_groups(scene, options.flip)) + " face(s)");
    const auto findings = check_orientation(scene);
    for (const auto& finding : findings)
        report.add(Kind::Warning,
                   describe(finding, scene) +
                       (options.orient_fix || finding.to_flip.empty()
                            ? ""
                            : "; --orient fix would flip them, or --flip the group"));
    std::vector<bool> turned(scene.polygons.size(), false);
    if (options.orient_fix) {
        report_flips(fix_orientation(scene, findings), "", report);
        // With closed objects facing outward, rays tell which way open surfaces face.
        const auto facing = check_facing_by_visibility(scene);
        for (const auto& finding : facing) report.add(Kind::Warning, describe(finding, scene));
        report_flips(fix_orientation(scene, facing), " (visibility)", report);
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
