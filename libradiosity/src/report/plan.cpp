// A calculation surface's plan for the report: false-colour cells, isolux lines labelled in
// lux, the luminaires over it, and a legend; SVG in pixels (the page prints it at A4 width).
#include "radfmt/container.hpp"
#include "radiosity/base64.hpp"
#include "radiosity/contours.hpp"
#include "radiosity/falsecolour.hpp"
#include "radiosity/image_io.hpp"
#include "radiosity/report.hpp"
#include "report/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

namespace rad {
namespace {
using report_text::px;
using report_text::short_number;

constexpr double kMargin = 12, kLegendWidth = 90, kScaleBarHeight = 26;

std::string colour_hex(std::array<std::uint8_t, 3> c) {
    char text[8];
    std::snprintf(text, sizeof text, "#%02x%02x%02x", c[0], c[1], c[2]);
    return text;
}

// Where the plan puts a point of the surface given in metres along u and v from the
// calculation area's corner: u to the right, v up (the surface seen from its front); a
// surface facing down (a ceiling) v down, as a reflected ceiling plan: seen from above, the
// same way round as the floor under it.
struct PlanFrame {
    double scale = 1, left = 0, corner = 0; // px per m; the area corner's pixel
    bool reflected = false;
    double x(double u_m) const { return left + u_m * scale; }
    double y(double v_m) const { return reflected ? corner + v_m * scale : corner - v_m * scale; }
};

PlanFrame frame_of(const SurfaceGrid& grid, const PlanScale& size) {
    const double whole_u = grid.width_m + 2 * grid.border_m;
    const double whole_v = grid.depth_m + 2 * grid.border_m;
    PlanFrame f;
    f.scale = std::min(size.width / whole_u, size.height / whole_v);
    f.left = kMargin + grid.border_m * f.scale;
    f.reflected = reflected_ceiling_plan(grid);
    f.corner = f.reflected ? kMargin + grid.border_m * f.scale
                           : kMargin + whole_v * f.scale - grid.border_m * f.scale;
    return f;
}

// A scale bar under the plan: a round length about a quarter of its width, in metres.
std::string scale_bar_svg(const PlanFrame& f, double left, double top, double plan_width) {
    const double target = plan_width / 4 / f.scale; // m
    double metres = std::pow(10.0, std::floor(std::log10(target)));
    for (const double step : {2.0, 5.0})
        if (metres * step <= target) metres = std::pow(10.0, std::floor(std::log10(target))) * step;
    const double length = metres * f.scale;
    std::string out = "<g class=\"scale-bar\" data-metres=\"" + short_number(metres) + "\">";
    for (int k = 0; k < 4; ++k)
        out += "<rect x=\"" + px(left + k * length / 4) + "\" y=\"" + px(top) + "\" width=\"" +
               px(length / 4) + "\" height=\"5\" fill=\"" + (k % 2 ? "#fff" : "#111") +
               "\" stroke=\"#111\" stroke-width=\"0.8\"/>";
    out += "<text x=\"" + px(left) + "\" y=\"" + px(top + 17) + "\">0</text><text x=\"" +
           px(left + length - 4) + "\" y=\"" + px(top + 17) + "\">" + short_number(metres) +
           " m</text>";
    return out + "</g>";
}

// Bilinear between a square's corners a (0, 0), b (1, 0), c (0, 1), d (1, 1) at (fu, fv).
double bilinear(double a, double b, double c, double d, double fu, double fv) {
    return (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d);
}

// The value at (u, v) in sensor units (sensor (c, r) at (c, r)): bilinear between the four
// sensors around it, flat past the outer ones; where one of the four has no value, the
// nearest sensor's (NaN when it has none: grey).
double field_at(std::span<const double> values, long columns, long rows, double u, double v) {
    u = std::clamp(u, 0.0, double(columns - 1));
    v = std::clamp(v, 0.0, double(rows - 1));
    const long c0 = std::min(long(u), columns - 1), r0 = std::min(long(v), rows - 1);
    const long c1 = std::min(c0 + 1, columns - 1), r1 = std::min(r0 + 1, rows - 1);
    const double fu = u - double(c0), fv = v - double(r0);
    const auto at = [&](long c, long r) { return values[std::size_t(r * columns + c)]; };
    const double a = at(c0, r0), b = at(c1, r0), c = at(c0, r1), d = at(c1, r1);
    if (std::isnan(a) || std::isnan(b) || std::isnan(c) || std::isnan(d))
        return at(std::lround(u), std::lround(v));
    return bilinear(a, b, c, d, fu, fv);
}

// The calculation area in smooth false colour: an image (two pixels a plan pixel) whose every
// pixel takes the bilinear interpolation of the sensors around it; points without a value grey.
std::string cells_svg(const ReportSurface& s, std::span<const double> values, const PlanFrame& f,
                      double top) {
    const auto& g = s.grid;
    const double left = f.x(0), right = f.x(g.width_m);
    const double upper = std::min(f.y(0), f.y(g.depth_m)), lower = std::max(f.y(0), f.y(g.depth_m));
    const int width = std::max(1, int(std::lround(2 * (right - left))));
    const int height = std::max(1, int(std::lround(2 * (lower - upper))));
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // The pixel's centre in metres along u and v, then in sensor units.
            const double u_m = (x + 0.5) / width * g.width_m;
            const double py = upper + (y + 0.5) / height * (lower - upper);
            const double v_m = f.reflected ? (py - f.corner) / f.scale : (f.corner - py) / f.scale;
            const double value =
                field_at(values, g.columns, g.rows, u_m / g.width_m * double(g.columns) - 0.5,
                         v_m / g.depth_m * double(g.rows) - 0.5);
            const auto colour = std::isnan(value) ? std::array<std::uint8_t, 3>{187, 187, 187}
                                                  : false_colour(value / top);
            std::copy(colour.begin(), colour.end(),
                      pixels.begin() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3);
        }
    return "<image class=\"cells\" x=\"" + px(left) + "\" y=\"" + px(upper) + "\" width=\"" +
           px(right - left) + "\" height=\"" + px(lower - upper) +
           "\" preserveAspectRatio=\"none\" href=\"data:image/png;base64," +
           base64(encode_png_rgb8(width, height, pixels)) + "\"/>";
}

struct PlacedLuminaire {
    double x = 0, y = 0;
    std::string name;
    std::string outline; // its luminous opening at its real size: an SVG shape, or empty
};

// A luminaire's opening in the plan (px): its rectangle (length along C0, width along C90) or
// disc, from the photometric file, turned as the layout turns it; empty when it has no size.
std::string opening_outline(const LuminaireSet& set, const Luminaire& l, const Vec3& unit_u,
                            const Vec3& unit_v, const PlanFrame& f, double u, double v) {
    const auto& p = set.photometries[l.photometry];
    if (!(p.length > 0)) return "";
    if (p.round)
        return "<circle class=\"opening\" cx=\"" + px(f.x(u)) + "\" cy=\"" + px(f.y(v)) +
               "\" r=\"" + px(0.5 * p.length * f.scale) + "\"/>";
    const double a[2] = {dot(l.c0, unit_u), dot(l.c0, unit_v)};
    const double b[2] = {dot(l.c90, unit_u), dot(l.c90, unit_v)};
    std::string d;
    for (const auto& [i, j] : {std::pair{1, 1}, {1, -1}, {-1, -1}, {-1, 1}}) {
        const double cu = u + 0.5 * (i * p.length * a[0] + j * p.width * b[0]);
        const double cv = v + 0.5 * (i * p.length * a[1] + j * p.width * b[1]);
        report_text::path_to(d, d.empty() ? 'M' : 'L', f.x(cu), f.y(cv));
    }
    return "<path class=\"opening\" d=\"" + d + "Z\"/>";
}

// The luminaires over (or under) a horizontal surface, wholly or in part, where the plan draws
// them (clipped to the surface).
std::vector<PlacedLuminaire> luminaires_over(const SurfaceGrid& g, const PlanFrame& f,
                                             const LuminaireSet* set, double metres_per_unit) {
    std::vector<PlacedLuminaire> out;
    if (!set || !horizontal_plan(g)) return out;
    const Vec3 unit_u = normalized(g.column_step), unit_v = normalized(g.row_step);
    for (const auto& l : set->luminaires) {
        const Vec3 offset = l.position - g.origin;
        const double u = dot(offset, unit_u) * metres_per_unit;
        const double v = dot(offset, unit_v) * metres_per_unit;
        // Partly over it counts: the opening's half-size past the surface and its border.
        const auto& p = set->photometries[l.photometry];
        const double reach =
            0.5 * std::max({p.length > 0 ? p.length : 0.0, p.width > 0 ? p.width : 0.0});
        const double b = g.border_m + reach;
        if (u < -b || v < -b || u > g.width_m + b || v > g.depth_m + b) continue;
        out.push_back({f.x(u), f.y(v), l.name, opening_outline(*set, l, unit_u, unit_v, f, u, v)});
    }
    return out;
}

// Where a label may go: apart from the labels placed and off the luminaires.
struct LabelPlaces {
    struct Taken {
        double x, y, radius;
    };
    std::vector<Taken> taken;
    bool free(double x, double y, double spacing) const {
        return std::none_of(taken.begin(), taken.end(), [&](const Taken& t) {
            return std::hypot(t.x - x, t.y - y) < std::min(t.radius, spacing);
        });
    }
};

// The segment whose middle lies farthest from every place taken.
std::size_t freest_segment(const std::vector<IsoSegment>& pixels, const LabelPlaces& places) {
    std::size_t best = 0;
    double best_distance = -1;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        const double mx = (pixels[k].x0 + pixels[k].x1) / 2, my = (pixels[k].y0 + pixels[k].y1) / 2;
        double nearest = 1e300;
        for (const auto& t : places.taken)
            nearest = std::min(nearest, std::hypot(t.x - mx, t.y - my));
        if (nearest > best_distance) best = k, best_distance = nearest;
    }
    return best;
}

// Up to four labels on a level's segments (pixel coordinates), 70 px apart from other labels;
// when none fits, one at 32 px; when none fits either, one where it is most apart: every line
// drawn has its value on it.
std::string label_level(const std::vector<IsoSegment>& pixels, const std::string& text,
                        LabelPlaces& places) {
    const auto label = [&](std::size_t k) {
        const double mx = (pixels[k].x0 + pixels[k].x1) / 2, my = (pixels[k].y0 + pixels[k].y1) / 2;
        places.taken.push_back({mx, my, 70});
        return "<text class=\"isolabel\" data-level=\"" + text + "\" x=\"" + px(mx) + "\" y=\"" +
               px(my + 4) + "\">" + text + "</text>";
    };
    std::string out;
    const std::size_t n = pixels.size();
    std::size_t stride = std::max<std::size_t>(1, n / 5);
    while (std::gcd(stride, n) != 1) ++stride; // visits every segment, spread out
    int count = 0;
    for (const double spacing : {70.0, 32.0}) {
        const int most = spacing > 50 ? 4 : 1;
        for (std::size_t i = 0, k = n / 2; i < n && count < most; ++i, k = (k + stride) % n) {
            const double mx = (pixels[k].x0 + pixels[k].x1) / 2,
                         my = (pixels[k].y0 + pixels[k].y1) / 2;
            if (!places.free(mx, my, spacing)) continue;
            out += label(k);
            ++count;
        }
        if (count) break;
    }
    if (!count && n > 0) out += label(freest_segment(pixels, places));
    return out;
}

// The sensors' values on a grid `refine` times finer between their centres, bilinear in each
// square of four sensors (NaN where one of them has no value): isolines drawn on it follow the
// smooth colours, and along any grid line they are linear, as the bilinear field is.
// Four times finer, less where the sensors are already about a pixel apart (a large grid's
// lines would only grow the page).
int refinement(long columns, long rows) {
    return int(std::clamp(200 / std::max(columns, rows), 1L, 4L));
}
struct FineGrid {
    std::vector<double> values;
    long columns = 0, rows = 0;
    int refine = 1;
};
FineGrid refined(std::span<const double> values, long columns, long rows) {
    FineGrid fine;
    const long kRefine = fine.refine = refinement(columns, rows);
    fine.columns = (columns - 1) * kRefine + 1;
    fine.rows = (rows - 1) * kRefine + 1;
    fine.values.resize(std::size_t(fine.columns * fine.rows));
    const auto at = [&](long c, long r) { return values[std::size_t(r * columns + c)]; };
    for (long j = 0; j < fine.rows; ++j)
        for (long i = 0; i < fine.columns; ++i) {
            const long c0 = std::min(i / kRefine, std::max(0L, columns - 2));
            const long r0 = std::min(j / kRefine, std::max(0L, rows - 2));
            const long c1 = std::min(c0 + 1, columns - 1), r1 = std::min(r0 + 1, rows - 1);
            const double fu = double(i) / kRefine - double(c0),
                         fv = double(j) / kRefine - double(r0);
            const double a = at(c0, r0), b = at(c1, r0), c = at(c0, r1), d = at(c1, r1);
            fine.values[std::size_t(j * fine.columns + i)] = bilinear(a, b, c, d, fu, fv);
        }
    return fine;
}

// The isolines, each level one path in pixels, with its labels.
std::string isolines_svg(const ReportSurface& s, std::span<const double> values,
                         const std::string& quantity, const PlanFrame& f,
                         const std::vector<PlacedLuminaire>& luminaires) {
    const auto& g = s.grid;
    const double du = g.width_m / double(g.columns), dv = g.depth_m / double(g.rows);
    // Sensor (c, r) at pixel (x0 + c dx, y0 - r dy).
    const double x0 = f.x(du / 2), y0 = f.y(dv / 2), dx = du * f.scale;
    const double dy = f.y(0) - f.y(dv); // negative on a reflected plan
    // The sensors' frame, to more digits than the drawing's (a test maps the lines' ends back).
    char frame[160];
    std::snprintf(frame, sizeof frame,
                  "data-sensor-origin=\"%.6f %.6f\" data-sensor-step=\"%.6f %.6f\"", x0, y0, dx,
                  dy);
    std::string out = "<g class=\"isolux\" data-quantity=\"" + quantity + "\" " + frame + ">";
    std::string labels;
    LabelPlaces places;
    for (const auto& l : luminaires) places.taken.push_back({l.x, l.y, 22});
    const auto range = illuminance_stats(values); // the finite values' min and max
    const auto fine = refined(values, g.columns, g.rows);
    for (const double level : contour_levels(range.min, range.max)) {
        auto segments = isolines(fine.values, fine.columns, fine.rows, level);
        if (segments.empty()) continue;
        std::string d;
        for (auto& seg : segments) {
            const double k = 1.0 / fine.refine; // fine units to the sensors'
            seg = {x0 + k * seg.x0 * dx, y0 - k * seg.y0 * dy, x0 + k * seg.x1 * dx,
                   y0 - k * seg.y1 * dy};
            d += 'M';
            d += px(seg.x0) + ' ' + px(seg.y0);
            d += 'L';
            d += px(seg.x1) + ' ' + px(seg.y1);
        }
        out +=
            "<path class=\"isoline\" data-level=\"" + short_number(level) + "\" d=\"" + d + "\"/>";
        labels += label_level(segments, short_number(level), places);
    }
    return out + labels + "</g>";
}

std::string luminaires_svg(const std::vector<PlacedLuminaire>& luminaires) {
    std::string out = "<g class=\"luminaires\">";
    for (const auto& [x, y, name, outline] : luminaires)
        out += "<g class=\"luminaire\" data-name=\"" + html_escape(name) + "\">" + outline +
               "<circle cx=\"" + px(x) + "\" cy=\"" + px(y) + "\" r=\"7\"/><path d=\"M" +
               px(x - 5) + " " + px(y - 5) + "L" + px(x + 5) + " " + px(y + 5) + "M" + px(x - 5) +
               " " + px(y + 5) + "L" + px(x + 5) + " " + px(y - 5) + "\"/><text x=\"" + px(x + 10) +
               "\" y=\"" + px(y - 8) + "\">" + html_escape(name) + "</text></g>";
    return out + "</g>";
}

std::string legend_svg(double left, double top_px, double height, double top_lux,
                       const std::string& unit) {
    std::string out = "<g class=\"legend\">";
    const int steps = 40;
    for (int k = 0; k < steps; ++k) {
        const double t = (k + 0.5) / steps;
        out += "<rect x=\"" + px(left) + "\" y=\"" + px(top_px + height * (1 - (k + 1.0) / steps)) +
               "\" width=\"16\" height=\"" + px(height / steps + 0.6) + "\" fill=\"" +
               colour_hex(false_colour(t)) + "\"/>";
    }
    for (int k = 0; k <= 4; ++k) {
        const double y = top_px + height * (1 - k / 4.0);
        out += "<text x=\"" + px(left + 22) + "\" y=\"" + px(y + 4) + "\">" +
               short_number(top_lux * k / 4) + "</text>";
    }
    out += "<text x=\"" + px(left) + "\" y=\"" + px(top_px - 6) + "\">" + unit + "</text>";
    return out + "</g>";
}

// The room cut at the plane: dark lines over the colours, as walls are drawn on a plan; glass
// (windows, glazed partitions) as a thin blue double line.
std::string cut_svg(const std::vector<PlanSegment>& cut, const PlanFrame& f) {
    std::string solid, glass;
    for (const auto& c : cut) {
        auto& d = c.glass ? glass : solid;
        report_text::path_to(d, 'M', f.x(c.u0), f.y(c.v0));
        report_text::path_to(d, 'L', f.x(c.u1), f.y(c.v1));
    }
    std::string out;
    if (!solid.empty())
        out += "<path class=\"cut\" d=\"" + solid +
               "\" fill=\"none\" stroke=\"#1a1a1a\" stroke-width=\"1.6\" "
               "stroke-linecap=\"round\"/>";
    if (!glass.empty())
        out += "<path class=\"cut-glass\" d=\"" + glass +
               "\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"4\"/><path d=\"" + glass +
               "\" fill=\"none\" stroke=\"#fff\" stroke-width=\"1.5\"/>";
    return out;
}

// A north arrow in a circle centred at (cx, cy), pointing where north lies on this plan: north
// (degrees from the scene's -Z towards +X) in the surface's u and v, v up the page (down on a
// reflected ceiling plan). Empty when north is unknown or lies across the surface.
std::string north_svg(const SurfaceGrid& g, const PlanFrame& f, double north_deg, double cx,
                      double cy) {
    if (!std::isfinite(north_deg)) return "";
    const double n = north_deg * std::numbers::pi / 180;
    const Vec3 north{std::sin(n), 0, -std::cos(n)};
    const double du = dot(north, normalized(g.column_step));
    const double dv = dot(north, normalized(g.row_step));
    const double length = std::hypot(du, dv);
    if (length < 0.5) return "";
    const double x = du / length, y = (f.reflected ? dv : -dv) / length; // page direction
    const double r = 15;
    const auto at = [&](double along, double across) {
        return px(cx + x * along - y * across) + "," + px(cy + y * along + x * across);
    };
    std::string out = "<g class=\"north\" data-north-deg=\"" + short_number(north_deg) +
                      "\" data-dx=\"" + report_text::fixed(x, 3) + "\" data-dy=\"" +
                      report_text::fixed(y, 3) + "\">";
    out += "<circle cx=\"" + px(cx) + "\" cy=\"" + px(cy) + "\" r=\"" + px(r) +
           "\" fill=\"#fff\" fill-opacity=\"0.85\" stroke=\"#111\" stroke-width=\"0.8\"/>";
    out += "<polygon points=\"" + at(r - 3, 0) + " " + at(-r + 5, 5) + " " + at(-r + 9, 0) + " " +
           at(-r + 5, -5) + "\" fill=\"#111\"/>";
    out += "<text x=\"" + px(cx + x * (r + 8)) + "\" y=\"" + px(cy + y * (r + 8) + 4) +
           "\" text-anchor=\"middle\" font-weight=\"bold\">N</text>";
    return out + "</g>";
}

} // namespace

std::string surface_plan_svg(const ReportSurface& s, std::span<const double> values,
                             const PlanScale& scale, const LuminaireSet* luminaires,
                             double metres_per_unit) {
    const auto& g = s.grid;
    const PlanFrame f = frame_of(g, scale);
    const double whole_u = (g.width_m + 2 * g.border_m) * f.scale;
    const double whole_v = (g.depth_m + 2 * g.border_m) * f.scale;
    const double width = kMargin * 2 + whole_u + kLegendWidth;
    // North goes under the legend: the plan is tall enough for it where north is known.
    const bool north = horizontal_plan(g) && std::isfinite(scale.north_deg);
    const double legend_height = std::min(whole_v, 300.0) - 16;
    const double north_y = kMargin + 16 + legend_height + 44;
    const double height =
        std::max({kMargin * 2 + whole_v + kScaleBarHeight, 180.0, north ? north_y + 30 : 0.0});
    const auto range = illuminance_stats(values);
    const double top = scale.top > 0 ? scale.top : false_colour_top(range.count ? range.max : 1);
    std::string out = "<svg class=\"plan\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                      px(width) + "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) +
                      " " + px(height) + "\" role=\"img\" aria-label=\"" + scale.quantity +
                      " plan of " + html_escape(s.surface.name) + "\">";
    // The whole surface (its border band shows as the background), then the area computed.
    // (its outline left to the cut where there is one: a doorway shows as a gap)
    out += std::string("<rect class=\"surface") + (s.cut.empty() ? "" : " cut-drawn") + "\" x=\"" +
           px(kMargin) + "\" y=\"" + px(kMargin) + "\" width=\"" + px(whole_u) + "\" height=\"" +
           px(whole_v) + "\"/>";
    // What is drawn over the surface stays on it: a luminaire partly over it is cut at its edge.
    const std::string clip =
        "clip-" +
        radfmt::hash_hex(radfmt::hash_bytes((s.surface.name + "\n" + scale.quantity).data(),
                                            s.surface.name.size() + 1 + scale.quantity.size()));
    out += "<clipPath id=\"" + clip + "\"><rect x=\"" + px(kMargin) + "\" y=\"" + px(kMargin) +
           "\" width=\"" + px(whole_u) + "\" height=\"" + px(whole_v) + "\"/></clipPath>";
    out += cells_svg(s, values, f, top);
    out += cut_svg(s.cut, f);
    const auto placed = luminaires_over(g, f, luminaires, metres_per_unit);
    out += "<g clip-path=\"url(#" + clip + ")\">" +
           isolines_svg(s, values, scale.quantity, f, placed) + luminaires_svg(placed) + "</g>";
    out += scale_bar_svg(f, kMargin, kMargin + whole_v + 8, whole_u);
    // The surface's overall dimensions, under its right-hand corner.
    out += "<text class=\"dimensions\" x=\"" + px(kMargin + whole_u) + "\" y=\"" +
           px(kMargin + whole_v + 20) + "\" text-anchor=\"end\">" +
           report_text::fixed(g.width_m + 2 * g.border_m, 2) + " m &#215; " +
           report_text::fixed(g.depth_m + 2 * g.border_m, 2) + " m</text>";
    out += legend_svg(kMargin * 2 + whole_u + 10, kMargin + 16, legend_height, top, scale.unit);
    if (north) out += north_svg(g, f, scale.north_deg, kMargin * 2 + whole_u + 40, north_y);
    return out + "</svg>";
}

} // namespace rad
