// The report's key plan: where each horizontal calculation surface lies in the room.
#include "radiosity/report.hpp"
#include "report/number_text.hpp"

#include <algorithm>
#include <cmath>

namespace rad {
namespace {
using report_text::px;

constexpr double kWidth = 420, kHeight = 300, kMargin = 14;

// Scene (x, z) to the key plan's pixels: x to the right, z down.
struct KeyFrame {
    double scale = 1, x0 = 0, z0 = 0;
    double x(double scene_x) const { return kMargin + (scene_x - x0) * scale; }
    double y(double scene_z) const { return kMargin + (scene_z - z0) * scale; }
};

// The room as the first horizontal surface facing up cuts it (its plan_cut: walls, doors,
// furniture at that height), in the key plan's frame; nothing when no surface has a cut.
std::string key_plan_cut(const ReportInput& in, const KeyFrame& f) {
    for (const auto& s : in.surfaces) {
        if (s.grid.normal[1] < 0.9 || s.cut.empty()) continue;
        const Vec3 u = normalized(s.grid.column_step), v = normalized(s.grid.row_step);
        const double units = 1 / in.metres_per_unit; // scene units a metre
        std::string d;
        const auto to = [&](char mark, double cu, double cv) {
            const Vec3 p = s.grid.origin + u * (cu * units) + v * (cv * units);
            report_text::path_to(d, mark, f.x(p[0]), f.y(p[2]));
        };
        for (const auto& c : s.cut) {
            to('M', c.u0, c.v0);
            to('L', c.u1, c.v1);
        }
        return "<path class=\"cut\" data-surface=\"" + html_escape(s.surface.name) + "\" d=\"" + d +
               "\" fill=\"none\" stroke=\"#222\" stroke-width=\"1.4\"/>";
    }
    return "";
}

} // namespace

std::string key_plan_svg(const ReportInput& in) {
    if (!in.room) return "";
    const Box& box = in.room->bounds;
    const double w = box.hi[0] - box.lo[0], d = box.hi[2] - box.lo[2];
    if (!(w > 0) || !(d > 0)) return "";
    KeyFrame f;
    f.scale = std::min((kWidth - 2 * kMargin) / w, (kHeight - 2 * kMargin) / d);
    f.x0 = box.lo[0], f.z0 = box.lo[2];
    const double width = 2 * kMargin + w * f.scale, height = 2 * kMargin + d * f.scale;
    std::string out = "<svg class=\"key-plan\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                      px(width) + "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) +
                      " " + px(height) + "\" role=\"img\" aria-label=\"key plan\">";
    out += "<rect class=\"room\" x=\"" + px(f.x(box.lo[0])) + "\" y=\"" + px(f.y(box.lo[2])) +
           "\" width=\"" + px(w * f.scale) + "\" height=\"" + px(d * f.scale) + "\"/>";
    // Labels already placed: an area whose label would fall on one (two areas with one
    // corner, a work plane and a cylindrical surface over the same floor) goes a line lower.
    std::vector<std::pair<double, double>> labels;
    for (const auto& s : in.surfaces) {
        // Areas facing up: walls have no place in a plan, and a ceiling would cover it.
        if (s.grid.normal[1] < 0.9) continue;
        const auto& c = s.surface;
        const auto& g = s.grid;
        // The calculation area (less its border band).
        const Vec3 across = g.column_step * double(g.columns), along = g.row_step * double(g.rows);
        double lo_x = 1e300, hi_x = -1e300, lo_z = 1e300, hi_z = -1e300;
        for (const Vec3& p :
             {g.origin, g.origin + across, g.origin + along, g.origin + across + along}) {
            lo_x = std::min(lo_x, p[0]), hi_x = std::max(hi_x, p[0]);
            lo_z = std::min(lo_z, p[2]), hi_z = std::max(hi_z, p[2]);
        }
        const double label_x = f.x(lo_x) + 3;
        double label_y = f.y(lo_z) + 12;
        while (std::any_of(labels.begin(), labels.end(), [&](const auto& l) {
            return std::abs(l.first - label_x) < 40 && std::abs(l.second - label_y) < 11;
        }))
            label_y += 12;
        labels.emplace_back(label_x, label_y);
        out += "<g class=\"area\" data-surface=\"" + html_escape(c.name) + "\"><rect x=\"" +
               px(f.x(lo_x)) + "\" y=\"" + px(f.y(lo_z)) + "\" width=\"" +
               px((hi_x - lo_x) * f.scale) + "\" height=\"" + px((hi_z - lo_z) * f.scale) +
               "\"/><text x=\"" + px(label_x) + "\" y=\"" + px(label_y) + "\">" +
               html_escape(c.name) + "</text></g>";
    }
    out += key_plan_cut(in, f);
    if (in.luminaires)
        for (const auto& l : in.luminaires->luminaires)
            out += "<circle class=\"luminaire\" cx=\"" + px(f.x(l.position[0])) + "\" cy=\"" +
                   px(f.y(l.position[2])) + "\" r=\"3\"/>";
    return out + "</svg>";
}

} // namespace rad
