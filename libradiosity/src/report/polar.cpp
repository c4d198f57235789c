// A luminaire type's polar intensity curve for the report: the C0-C180 and C90-C270 planes
// in cd/klm of the luminaire's flux, gamma 0 (the nadir) pointing down; SVG.
#include "radiosity/report.hpp"
#include "report/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace rad {
namespace {
using report_text::px;

constexpr double kSize = 300, kRadius = 125;

// The file's intensity (no maintenance, no TILT) in the C plane `c_deg` at `gamma_deg`, in
// the luminaire's own frame (so that type A and B files are drawn as mounted).
double file_intensity(const LuminaireSet& set, const Luminaire& l, double c_deg, double gamma_deg) {
    const double c = c_deg * std::numbers::pi / 180, g = gamma_deg * std::numbers::pi / 180;
    const Vec3 d = l.nadir * std::cos(g) + (l.c0 * std::cos(c) + l.c90 * std::sin(c)) * std::sin(g);
    const double loss = l.maintenance * l.tilt_factor;
    return loss > 0 ? set.intensity(l, normalized(d)) / loss : 0;
}

// One half-plane pair as a closed path: `right_c` drawn to the right, `left_c` to the left.
std::string curve_path(const LuminaireSet& set, const Luminaire& l, double right_c, double left_c,
                       double per_klm, double scale) {
    std::string d;
    const double cx = kSize / 2, cy = kSize / 2;
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k <= 180; ++k) {
            const double gamma = side == 0 ? k : 180 - k;
            const double c = side == 0 ? right_c : left_c;
            const double r = file_intensity(set, l, c, gamma) * per_klm * scale;
            const double a = gamma * std::numbers::pi / 180;
            const double x = cx + (side == 0 ? 1 : -1) * r * std::sin(a), y = cy + r * std::cos(a);
            report_text::path_to(d, d.empty() ? 'M' : 'L', x, y);
        }
    return d + "Z";
}

} // namespace

std::string polar_curve_svg(const LuminaireSet& set, const Luminaire& l) {
    const double flux = set.photometry_flux[l.photometry];
    const double per_klm = flux > 0 ? 1000 / flux : 0;
    double peak = 0;
    for (const double c : {0.0, 90.0, 180.0, 270.0})
        for (int g = 0; g <= 180; ++g)
            peak = std::max(peak, file_intensity(set, l, c, g) * per_klm);
    // Rings at round values up to the peak.
    const double decade = std::pow(10.0, std::floor(std::log10(std::max(peak, 1e-9))));
    double ring = decade;
    for (const double m : {0.1, 0.2, 0.25, 0.5, 1.0})
        if (peak / (m * decade) <= 5) {
            ring = m * decade;
            break;
        }
    const double top = std::ceil(peak / ring - 1e-9) * ring;
    const double scale = top > 0 ? kRadius / top : 0;
    const double cx = kSize / 2, cy = kSize / 2;
    std::string out = "<svg class=\"polar\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                      px(kSize) + "\" height=\"" + px(kSize + 24) + "\" viewBox=\"0 0 " +
                      px(kSize) + " " + px(kSize + 24) +
                      "\" role=\"img\" aria-label=\"polar curve\">";
    out += "<g class=\"grid\">";
    for (double r = ring; r <= top + 1e-9; r += ring)
        out += "<circle cx=\"" + px(cx) + "\" cy=\"" + px(cy) + "\" r=\"" + px(r * scale) +
               "\"/><text x=\"" + px(cx + 3) + "\" y=\"" + px(cy - r * scale - 2) + "\">" +
               lux_text(r) + "</text>";
    for (int a = 0; a < 180; a += 30) {
        const double t = a * std::numbers::pi / 180;
        out += "<path d=\"M" + px(cx - kRadius * std::sin(t)) + " " +
               px(cy - kRadius * std::cos(t)) + "L" + px(cx + kRadius * std::sin(t)) + " " +
               px(cy + kRadius * std::cos(t)) + "\"/>";
    }
    // Gamma from the nadir (0, down) to the zenith (180, up), outside the rim on the right.
    for (int g = 0; g <= 180; g += 30) {
        const double t = g * std::numbers::pi / 180, r = kRadius + 11;
        // (180 beside the top, where the rings' values are written)
        const double shift = g == 180 ? -16 : 0;
        out += "<text class=\"gamma\" data-gamma=\"" + std::to_string(g) + "\" x=\"" +
               px(cx + r * std::sin(t) + shift) + "\" y=\"" + px(cy + r * std::cos(t) + 3) +
               "\" text-anchor=\"middle\" font-size=\"8\">" + std::to_string(g) + "&#176;</text>";
    }
    out += "</g>";
    out += "<path class=\"c0\" d=\"" + curve_path(set, l, 0, 180, per_klm, scale) + "\"/>";
    out += "<path class=\"c90\" d=\"" + curve_path(set, l, 90, 270, per_klm, scale) + "\"/>";
    out += "<text x=\"4\" y=\"" + px(kSize + 18) +
           "\"><tspan class=\"c0\">&#8212; C0-C180</tspan>  <tspan class=\"c90\">- - C90-C270"
           "</tspan>  cd/klm</text>";
    return out + "</svg>";
}

} // namespace rad
