// The imprinting pass: contacts cut into faces, hidden regions removed, reported.
#include "radiosity/build_mesh.hpp"

#include <cstdio>
#include <map>

namespace rad {

namespace {

std::map<std::uint32_t, double> area_by_group(const Scene& scene) {
    std::map<std::uint32_t, double> area;
    for (const auto& polygon : scene.polygons) {
        std::vector<radfmt::Vec3> pts;
        for (const auto v : polygon.vertices) pts.push_back(scene.vertices[v]);
        area[polygon.group] += 0.5 * length(newell_normal(pts));
    }
    return area;
}

std::string summary(const Scene& scene, const ImprintReport& imprint) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "imprinted: contacts cut into %zu face(s) (area %.6g); %zu hidden region(s) "
                  "removed (area %.6g)",
                  imprint.faces_imprinted, imprint.area_imprinted, imprint.regions_removed,
                  imprint.area_removed);
    std::string line = text;
    if (!imprint.removed_lines.empty()) {
        line += scene.face_ranges.empty() ? ", from the face(s) at line" : ", from";
        for (std::size_t k = 0; k < imprint.removed_lines.size() && k < 8; ++k)
            line.append(k && !scene.face_ranges.empty() ? ", " : " ")
                .append(face_number(scene, imprint.removed_lines[k]));
        if (imprint.removed_lines.size() > 8) line += " ...";
    }
    return line + " (--no-imprint keeps the faces whole)";
}

} // namespace

void imprint_pass(Scene& scene, const std::vector<bool>& turned, double contact_gap,
                  MeshReport& report) {
    const auto group_area = area_by_group(scene);
    const auto imprint = imprint_contacts(scene, 1e-7, turned, contact_gap);
    // More than 1% of a group lost, not as footprints bounded by contact lines: worth a look.
    for (const auto& [group, area] : imprint.removed_by_group) {
        const double of = group_area.at(group);
        if (!(area > 0.01 * of)) continue;
        char text[400];
        std::snprintf(
            text, sizeof text,
            "imprinting removed %.6g of group %s's area %.6g (%.1f%%), bounded mostly "
            "by the faces' own outlines, as hidden inside or behind other geometry; if that "
            "is wrong, check which way the surfaces around it face (--orient fix) or "
            "use --no-imprint",
            area, scene.groups[group].c_str(), of, 100 * area / of);
        report.add(MeshReport::Kind::Warning, text);
    }
    if (imprint.faces_imprinted) report.add(MeshReport::Kind::Change, summary(scene, imprint));
}

} // namespace rad
