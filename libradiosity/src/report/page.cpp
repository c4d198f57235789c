// The report's page: title block, contents, summary, a page per calculation surface, the
// luminaires and the observers' glare; self-contained HTML with print rules for A4.
#include "radiosity/report.hpp"
#include "radiosity/ugr_table.hpp"

#include "radiosity/base64.hpp"
#include "report/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>

namespace rad {
namespace {
using report_text::fixed;
using report_text::short_number;

const char* kStyle = R"(
@page { size: A4; margin: 14mm 14mm 16mm 14mm; }
body { font: 10pt/1.35 "DejaVu Sans", Helvetica, Arial, sans-serif; color: #111; margin: 0 auto;
       max-width: 182mm; padding: 0 4mm; }
h1 { font-size: 18pt; margin: 0 0 4pt; } h2 { font-size: 13pt; margin: 14pt 0 6pt;
  border-bottom: 1px solid #444; } h3 { font-size: 11pt; margin: 10pt 0 4pt; }
table { border-collapse: collapse; margin: 4pt 0 8pt; break-inside: avoid; }
th, td { border: 1px solid #999; padding: 2pt 5pt; text-align: left; vertical-align: top; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.warning td, tr.warning th { color: #a00; }
table.schedule { font-size: 8pt; } table.schedule td { overflow-wrap: break-word; }
.title-block { border: 2px solid #222; padding: 8pt 10pt; margin-top: 6pt; }
.title-block table { margin: 0; } .title-block td, .title-block th { border: none; padding: 1pt 6pt 1pt 0; }
.title-block th { white-space: nowrap; }
.title-view { margin: 6pt 0; } .title-view img { width: 60%; }
.hash { font-family: "DejaVu Sans Mono", monospace; font-size: 8pt; }
.provenance { font-family: "DejaVu Sans Mono", monospace; font-size: 7.5pt; word-break: break-all; }
.pass { color: #0a6b1f; font-weight: bold; } .fail { color: #b00020; font-weight: bold; }
section.part { break-before: page; }
h2, h3 { break-after: avoid; } #room { break-inside: avoid; }
figure { margin: 6pt 0; break-inside: avoid; }
figure.view img { max-width: 100%; height: auto; }
code.command { font-size: 8pt; word-break: break-all; } figcaption { font-size: 9pt; color: #333; }
svg text { font: 11px "DejaVu Sans", Helvetica, Arial, sans-serif; fill: #111; }
svg.plan rect.surface { fill: #eee; stroke: #555; stroke-width: 1; }
svg.plan rect.surface.cut-drawn { stroke: none; }
table.point-table { font-size: 7pt; border-collapse: collapse; }
table.point-table td { padding: 1px 3px; }
svg.plan .isoline { fill: none; stroke: #000; stroke-width: 1.3; }
svg.plan .isolabel { font-weight: bold; paint-order: stroke; stroke: #fff; stroke-width: 3px;
  text-anchor: middle; }
svg.plan .luminaire circle { fill: #fff; stroke: #000; stroke-width: 1.2; }
svg.key-plan .room { fill: #f4f4f4; stroke: #333; stroke-width: 1.5; }
svg.key-plan .area rect { fill: rgba(40, 120, 200, 0.15); stroke: #1a5fa0; stroke-width: 1; }
svg.key-plan .luminaire { fill: #111; } svg.key-plan text { font-size: 10px; }
svg.plan .luminaire .opening { fill: #fff; fill-opacity: 0.75; stroke: #000; stroke-width: 1; }
svg.plan .luminaire path { stroke: #000; stroke-width: 1.2; }
svg.plan .luminaire text { paint-order: stroke; stroke: #fff; stroke-width: 3px; }
svg.polar .grid circle, svg.polar .grid path { fill: none; stroke: #bbb; stroke-width: 0.8; }
svg.polar path.c0 { fill: none; stroke: #b00020; stroke-width: 1.6; }
svg.polar path.c90 { fill: none; stroke: #1040b0; stroke-width: 1.6; stroke-dasharray: 5 3; }
svg.polar tspan.c0 { fill: #b00020; } svg.polar tspan.c90 { fill: #1040b0; }
.polars, .plans { display: flex; flex-wrap: wrap; gap: 8pt; }
.polars figure { width: 300px; }
.plans figure { width: min-content; }

.note { font-size: 9pt; color: #333; }
nav ol { margin: 2pt 0; }
table.surfaces td:first-child { white-space: nowrap; }
table.daylight { font-size: 9pt; }
.keep { break-inside: avoid; } table.ugr-table { font-size: 8pt; } table.ugr-table caption { text-align: left; font-size: 9pt; }
)";

std::string verdict_text(bool required, bool passes, bool close = false) {
    if (!required) return "<td>-</td>";
    const std::string within = close ? ", within the calculation's uncertainty" : "";
    return passes ? "<td class=\"pass\">meets" + within + "</td>"
                  : "<td class=\"fail\">fails" + within + "</td>";
}

// "± 3.2" for a figure's standard error (empty when it is not known): as lux, or to two
// decimals (three under 0.005) for a ratio or a percentage.
std::string error_text(double error, bool ratio = false) {
    if (!std::isfinite(error)) return "";
    return "± " + (ratio ? fixed(error, error >= 0.005 ? 2 : 3) : lux_text(error));
}

// What is asked of a surface, the quantities the file gives ("-": none).
struct Asked {
    const char *name, *relation;
    double value; // NaN: not asked
    const char* unit;
};
std::string asked_text(std::initializer_list<Asked> asked) {
    std::string out;
    for (const auto& a : asked)
        if (!std::isnan(a.value))
            out += (out.empty() ? "" : ", ") + std::string(a.name) + " " + a.relation + " " +
                   short_number(a.value) + a.unit;
    return out.empty() ? "-" : out;
}

std::string required_text(const Requirements& r) {
    return asked_text({{"Em", "&#8805;", r.em, " lx"},
                       {"U0", "&#8805;", r.u0, ""},
                       {"Emin", "&#8805;", r.emin, " lx"},
                       {"Emax/Emin", "&#8804;", r.max_over_min, ""}});
}

std::string daylight_required_text(const Requirements& r) {
    return asked_text({{"DF", "&#8805;", r.df, "%"},
                       {"sDA", "&#8805;", r.sda, "%"},
                       {"ASE", "&#8804;", r.ase, "%"}});
}

std::string cell(const std::string& text, const char* cls = "num") {
    return std::string("<td class=\"") + cls + "\">" + text + "</td>";
}

std::string report_kind(const ReportInput& in) {
    return in.daylight ? "Daylight report" : "Lighting report";
}

std::string title_block(const ReportInput& in) {
    std::string out = "<header class=\"title-block\"><h1>" + report_kind(in) + ": " +
                      html_escape(in.project) + "</h1><table>";
    out += "<tr><th>Project</th><td>" + html_escape(in.project) + "</td></tr>";
    if (!in.client.empty())
        out += "<tr><th>Client</th><td>" + html_escape(in.client) + "</td></tr>";
    if (!in.designer.empty())
        out += "<tr><th>Designer</th><td>" + html_escape(in.designer) + "</td></tr>";
    out += "<tr><th>Date</th><td>" + html_escape(in.date) + "</td></tr>";
    out += "<tr><th>Made by</th><td>" + html_escape(in.producer) + "</td></tr>";
    if (in.daylight) {
        out += "<tr><th>Units</th><td>daylight factor (DF): the illuminance at a point over the "
               "unobstructed outdoor horizontal illuminance under the " +
               html_escape(in.daylight_sky) + ", in %; lengths in metres</td></tr>";
        if (!in.weather.empty())
            out += "<tr><th>Year</th><td>" + html_escape(in.weather) +
                   "; occupied hours: " + html_escape(in.occupancy) + "</td></tr>";
    } else {
        out += "<tr><th>Units</th><td>illuminance in lux (lx), maintained: each luminaire's "
               "maintenance factor applied (see the schedule); luminance in cd/m&#178;; lengths "
               "in metres</td></tr>";
    }
    out += "</table>";
    // The first view of the room on the title block, as a designer's cover shows it.
    if (!in.views.empty()) {
        const auto& v = in.views.front();
        out += "<figure class=\"title-view\"><img alt=\"" + html_escape(v.name) +
               "\" src=\"data:image/png;base64," +
               base64(v.thumbnail_png.empty() ? v.png : v.thumbnail_png) + "\"><figcaption>" +
               html_escape(v.name) + "</figcaption></figure>";
    }
    out += "<h3>Inputs</h3><table>";
    for (const auto& [path, hash] : in.inputs)
        out += "<tr><td>" + html_escape(path) + "</td><td class=\"hash\">" + html_escape(hash) +
               "</td></tr>";
    out += "</table>";
    if (!in.provenance.empty()) {
        out += "<h3>How the solution was made</h3><ol class=\"provenance\">";
        for (const auto& line : in.provenance) out += "<li>" + html_escape(line) + "</li>";
        out += "</ol>";
    }
    return out + "</header>";
}

std::string contents(const ReportInput& in) {
    std::string out = "<nav id=\"contents\"><h2>Contents</h2><ol>";
    out += "<li><a href=\"#summary\">Summary</a></li>";
    if (in.room) out += "<li><a href=\"#room\">The room</a></li>";
    for (std::size_t k = 0; k < in.surfaces.size(); ++k)
        out += "<li><a href=\"#surface-" + std::to_string(k + 1) + "\">" +
               html_escape(in.surfaces[k].surface.name) + "</a></li>";
    if (in.luminaires) out += "<li><a href=\"#luminaires\">Luminaires</a></li>";
    if (in.energy) out += "<li><a href=\"#energy\">Energy (LENI)</a></li>";
    if (!in.observers.empty()) out += "<li><a href=\"#glare\">Glare (UGR)</a></li>";
    if (!in.daylight_glare.empty())
        out += "<li><a href=\"#daylight-glare\">Daylight glare (DGP)</a></li>";
    if (!in.views.empty()) out += "<li><a href=\"#views\">Views</a></li>";
    out += "<li><a href=\"#method\">Method</a></li>";
    return out + "</ol></nav>";
}

// The room: its size, its floor area and each surface's reflectance (from the mesh).
std::string room_section(const ReportInput& in) {
    const auto& room = *in.room;
    std::string out = "<section id=\"room\"><h2>The room</h2><p class=\"room-size\">Extent " +
                      fixed(room.size_m[0], 2) + " &#215; " + fixed(room.size_m[1], 2) +
                      " &#215; " + fixed(room.size_m[2], 2) + " m (x, y, z: the scene's bounds)";
    if (in.power_area_m2 > 0)
        out += "; floor area " + fixed(in.power_area_m2, 2) + " m&#178; (" +
               html_escape(in.power_area_what) + ")";
    out += ".</p><table class=\"room-surfaces\"><thead><tr><th>Surface (material)</th><th "
           "class=\"num\">Area (m&#178;)</th><th class=\"num\">Reflectance</th></tr></thead>"
           "<tbody>";
    for (const auto& m : room.materials)
        out += "<tr><td>" + html_escape(m.name) + (m.emits ? " (emits light)" : "") + "</td>" +
               cell(fixed(m.area_m2, 2)) + cell(fixed(m.reflectance, 2)) + "</tr>";
    out += "</tbody></table><p class=\"note\">Reflectance: the material's diffuse "
           "reflectance, luminous (0.265 R + 0.670 G + 0.065 B), as solved.</p>";
    if (const auto key = key_plan_svg(in); !key.empty())
        out += "<figure class=\"key\">" + key +
               "<figcaption>Key plan: the room from above (x to the right, z down, as the "
               "plans of the floor) with each horizontal calculation area and the luminaires "
               "(dots)" +
               std::string(key.find("class=\"cut\"") != std::string::npos
                               ? "; dark lines: the room cut at the first work plane's height"
                               : "") +
               ".</figcaption></figure>";
    return out + "</section>";
}

std::string surface_row(const ReportSurface& s, std::size_t index) {
    const auto& st = s.stats;
    const auto& r = s.surface.required;
    return "<tr data-surface=\"" + html_escape(s.surface.name) + "\"><td><a href=\"#surface-" +
           std::to_string(index + 1) + "\">" + html_escape(s.surface.name) + "</a></td><td>" +
           calc_kind_name(s.surface.kind) + "</td>" + cell(lux_text(st.mean, r.em)) +
           cell(lux_text(st.min, r.emin)) + cell(lux_text(st.max)) +
           cell(ratio_text(st.u0(), r.u0)) + cell(ratio_text(st.min_over_max())) + "<td>" +
           required_text(s.surface.required) + "</td>" +
           verdict_text(s.surface.required.of_light(), s.verdict.passes(), s.verdict.close()) +
           "</tr>";
}

std::string surfaces_table(const ReportInput& in) {
    std::string out = "<table class=\"surfaces\"><thead><tr><th>Surface</th><th>Kind</th>"
                      "<th class=\"num\">Em (lx)</th><th class=\"num\">Emin (lx)</th>"
                      "<th class=\"num\">Emax (lx)</th><th class=\"num\">U0</th>"
                      "<th class=\"num\">Emin/Emax</th><th>Required</th><th>Verdict</th></tr>"
                      "</thead><tbody>";
    for (std::size_t k = 0; k < in.surfaces.size(); ++k) out += surface_row(in.surfaces[k], k);
    return out + "</tbody></table>";
}

std::string ugr_text(double ugr) {
    return std::isnan(ugr) ? std::string("-") : fixed(ugr, 1);
}

std::string observers_table(const ReportInput& in) {
    std::string out = "<table class=\"observers\"><thead><tr><th>Observer</th>"
                      "<th class=\"num\">UGR</th><th class=\"num\">Limit</th><th>Verdict</th>"
                      "</tr></thead><tbody>";
    for (const auto& o : in.observers) {
        const bool limited = !std::isnan(o.observer.ugr_limit);
        const bool passes = !std::isnan(o.glare.ugr) ? o.glare.ugr <= o.observer.ugr_limit : true;
        out += "<tr data-observer=\"" + html_escape(o.observer.name) + "\"><td>" +
               html_escape(o.observer.name) + "</td>" + cell(ugr_text(o.glare.ugr)) +
               cell(limited ? fixed(o.observer.ugr_limit, 0) : "-") +
               verdict_text(limited, passes) + "</tr>";
    }
    return out + "</tbody></table>";
}

std::string percent(double share) {
    return fixed(100 * share, 1);
}

std::string daylight_table(const ReportInput& in) {
    const bool annual = !in.weather.empty();
    std::string out = "<table class=\"surfaces daylight\"><thead><tr><th>Surface</th><th>Kind"
                      "</th><th class=\"num\">DF mean (%)</th><th class=\"num\">DF median (%)"
                      "</th><th class=\"num\">DF min (%)</th><th class=\"num\">DF max (%)</th>"
                      "<th class=\"num\">DF &#8805; 2% (% of points)</th>";
    if (annual) out += "<th class=\"num\">sDA (%)</th><th class=\"num\">ASE (%)</th>";
    out += "<th>Required</th><th>Verdict</th></tr></thead><tbody>";
    for (std::size_t k = 0; k < in.surfaces.size(); ++k) {
        const auto& s = in.surfaces[k];
        const auto& d = s.daylight->summary;
        out += "<tr data-surface=\"" + html_escape(s.surface.name) + "\"><td><a href=\"#surface-" +
               std::to_string(k + 1) + "\">" + html_escape(s.surface.name) + "</a></td><td>" +
               calc_kind_name(s.surface.kind) + "</td>" + cell(fixed(d.mean, 2)) +
               cell(fixed(d.median, 2)) + cell(fixed(d.min, 2)) + cell(fixed(d.max, 2)) +
               cell(percent(d.above2));
        if (annual)
            out += cell(percent(s.daylight->metrics.sda)) + cell(percent(s.daylight->metrics.ase));
        out += "<td>" + daylight_required_text(s.surface.required) + "</td>" +
               verdict_text(s.surface.required.of_daylight(), s.daylight->verdict.passes(),
                            s.daylight->verdict.close()) +
               "</tr>";
    }
    return out + "</tbody></table>";
}

std::string summary(const ReportInput& in) {
    std::string out = "<section id=\"summary\"><h2>Summary</h2>";
    if (in.daylight) {
        out += daylight_table(in);
        out += "<p class=\"note\">DF: daylight factor; sDA: sDA300/50%, the share of points lit to "
               "300 lx or more by daylight for half the occupied hours or more; ASE: ASE1000,250h, "
               "the share of points the sun's beam alone lights to 1000 lx or more for over 250 "
               "occupied hours (IES LM-83).</p>";
        return out + "</section>";
    }
    if (!in.surfaces.empty()) out += surfaces_table(in);
    if (!in.observers.empty()) out += observers_table(in);
    out += "<p class=\"note\">Em: average maintained illuminance over a surface's calculation "
           "points; U0 = Emin/Em. Requirements are the ones given in the calculation-surfaces "
           "file.</p>";
    return out + "</section>";
}

// The calculation area and its grid, the first rows of a surface's table.
std::string grid_rows(const ReportSurface& s) {
    const auto& g = s.grid;
    return "<tr><th>Kind</th><td>" + std::string(calc_kind_name(s.surface.kind)) + "</td></tr>" +
           "<tr><th>Calculation area</th><td>" + fixed(g.width_m, 2) + " m &#215; " +
           fixed(g.depth_m, 2) + " m (border band " + fixed(g.border_m, 2) +
           " m left out)</td></tr><tr><th>Grid</th><td>" + std::to_string(g.columns) + " &#215; " +
           std::to_string(g.rows) + " points, spacing at most " + fixed(g.spacing_m, 3) +
           " m</td></tr>";
}

std::string figure_row(const char* name, const std::string& value, const char* cls,
                       const std::string& error = "") {
    return std::string("<tr><th>") + name + "</th><td class=\"num " + cls + "\">" + value +
           "</td>" + (error.empty() ? "" : "<td class=\"num error\">" + error + "</td>") + "</tr>";
}

// Two plans side by side across the page, at their own size (labels stay readable in print).
constexpr double kHalfWidth = 200, kHalfHeight = 330;

// EN 17037's daylight provision (daylight factor method): each level's target and minimum as
// daylight factors for the place, the shares of the plane at them, met or not.
std::string en17037_rows(const SurfaceDaylight& d) {
    const auto& e = *d.en17037;
    std::string out =
        "<tr><th>EN 17037 daylight provision</th><td class=\"en17037\" "
        "data-achieved=\"" +
        e.achieved() + "\">level achieved: <b>" + e.achieved() +
        "</b> (daylight factor method; E<sub>v,d,med</sub> " + fixed(e.median_lux, 0) +
        " lx, the median of the year's 4380 brightest hours of " + html_escape(d.median_source) +
        ")<table class=\"levels\"><thead><tr><th>"
        "Level</th><th class=\"num\">D<sub>T</sub> (%) over 50%</th><th "
        "class=\"num\">share</th><th class=\"num\">D<sub>TM</sub> (%) over "
        "95%</th><th class=\"num\">share</th><th>Verdict</th></tr></thead><tbody>";
    for (const auto& l : e.levels)
        out += "<tr data-level=\"" + std::string(l.name) + "\"><td>" + l.name + " (" +
               fixed(l.target_lux, 0) + " / " + fixed(l.minimum_lux, 0) + " lx)</td>" +
               cell(fixed(l.target_df, 2)) + cell(percent(l.target_share)) +
               cell(fixed(l.minimum_df, 2)) + cell(percent(l.minimum_share)) +
               (l.met ? "<td class=\"pass\">met</td>" : "<td class=\"fail\">not met</td>") +
               "</tr>";
    return out + "</tbody></table></td></tr>";
}

// EN 17037's daylight provision by the year's illuminance: each level's shares of the
// daylight hours in which its target reaches half of the plane and its minimum 95%.
std::string en17037_hourly_rows(const En17037Hourly& e) {
    std::string out = "<tr><th>EN 17037 by illuminance</th><td class=\"en17037-hourly\" "
                      "data-achieved=\"" +
                      e.achieved() + "\">level achieved: <b>" + e.achieved() +
                      "</b> (illuminance method: the year's hours, over its " +
                      std::to_string(e.daylight_hours) +
                      " daylight hours, the half with the most diffuse light; met when both "
                      "shares reach 50%)<table class=\"levels\"><thead><tr><th>Level</th>"
                      "<th class=\"num\">hours with E<sub>T</sub> over 50%</th>"
                      "<th class=\"num\">hours with E<sub>TM</sub> over 95%</th>"
                      "<th>Verdict</th></tr></thead><tbody>";
    for (const auto& l : e.levels)
        out += "<tr data-level=\"" + std::string(l.name) + "\"><td>" + l.name + " (" +
               fixed(l.target_lux, 0) + " / " + fixed(l.minimum_lux, 0) + " lx)</td>" +
               cell(percent(l.target_hours)) + cell(percent(l.minimum_hours)) +
               (l.met ? "<td class=\"pass\">met</td>" : "<td class=\"fail\">not met</td>") +
               "</tr>";
    return out + "</tbody></table></td></tr>";
}

// What the plan's caption says of the room cut at the plane (plan_cut), if anything is.
std::string cut_caption(const ReportSurface& s) {
    if (s.cut.empty()) return "";
    const bool glass =
        std::any_of(s.cut.begin(), s.cut.end(), [](const auto& c) { return c.glass; });
    return std::string("; dark lines: the room cut at the plane") +
           (glass ? ", blue double lines: glass cut there" : "");
}

// The values as a table laid out as the plan is (columns along u; rows with v up the page, or
// down on a reflected ceiling plan), for a small grid when asked (rad-report --point-tables).
constexpr long kPointTableColumns = 20, kPointTableSize = 400;
std::string point_table(const ReportInput& in, const ReportSurface& s,
                        std::span<const double> values, const std::string& unit,
                        const std::function<std::string(double)>& text) {
    if (!in.point_tables) return "";
    const auto& g = s.grid;
    if (g.columns > kPointTableColumns || g.size() > kPointTableSize)
        return "<p class=\"point-table-left-out\">Point table left out: " +
               std::to_string(g.columns) + " x " + std::to_string(g.rows) +
               " points (tables are printed up to " + std::to_string(kPointTableColumns) +
               " columns and " + std::to_string(kPointTableSize) + " points).</p>";
    std::string out = "<table class=\"point-table\"><caption>Point values (" + unit + ") of " +
                      html_escape(s.surface.name) + ", laid out as the plan above</caption><tbody>";
    const bool reflected = reflected_ceiling_plan(g);
    for (long k = 0; k < g.rows; ++k) {
        const long row = reflected ? k : g.rows - 1 - k;
        out += "<tr>";
        for (long column = 0; column < g.columns; ++column)
            out += "<td class=\"num\">" + text(values[std::size_t(row * g.columns + column)]) +
                   "</td>";
        out += "</tr>";
    }
    return out + "</tbody></table>";
}

std::string daylight_section(const ReportInput& in, const ReportSurface& s, std::size_t index) {
    const auto& d = *s.daylight;
    std::string out = "<section class=\"part surface\" id=\"surface-" + std::to_string(index + 1) +
                      "\"><h2>" + html_escape(s.surface.name) +
                      "</h2><table class=\"figures daylight\" data-surface=\"" +
                      html_escape(s.surface.name) + "\"><tbody>" + grid_rows(s);
    out += figure_row("DF mean (%)", fixed(d.summary.mean, 2), "df-mean",
                      error_text(d.mean_error, true));
    out += figure_row("DF median (%)", fixed(d.summary.median, 2), "df-median");
    out += figure_row("DF min (%)", fixed(d.summary.min, 2), "df-min");
    out += figure_row("DF max (%)", fixed(d.summary.max, 2), "df-max");
    out += figure_row("Points at 2% or more (%)", percent(d.summary.above2), "df-above2");
    if (d.summary.without)
        out += "<tr><th>Points without a value</th><td>" + std::to_string(d.summary.without) +
               " (inside or under objects; grey in the plan; in no figure)</td></tr>";
    if (d.annual) {
        // Their errors in percentage points, by the jackknife over the reflected light's
        // batches; ASE is the sun's beam alone, exact.
        const auto& e = d.metric_errors;
        const auto points = [](double error) {
            return std::isfinite(error) ? "± " + fixed(100 * error, 2) : std::string();
        };
        out += figure_row("sDA300/50% (%)", percent(d.metrics.sda), "sda", points(e.sda));
        out += figure_row("ASE1000,250h (%)", percent(d.metrics.ase), "ase", "± 0");
        out += figure_row("DA300 mean (% of hours)", percent(d.metrics.da300), "da300",
                          points(e.da300_mean));
        out += figure_row("UDI 100-3000 lx mean (% of hours)", percent(d.metrics.udi_useful), "udi",
                          points(e.udi_useful_mean));
    }
    if (d.en17037) out += en17037_rows(d);
    if (d.en17037_hourly) out += en17037_hourly_rows(*d.en17037_hourly);
    // The two plans side by side when they fit across the page, else one under the other.
    out += "<tr><th>Required</th><td>" + daylight_required_text(s.surface.required) + "</td></tr>";
    if (!d.at_budget.empty())
        out += "<tr><th>Points short of the accuracy</th><td>" +
               std::to_string(d.at_budget.size()) + " (stopped at the ray budget)</td></tr>";
    out += "<tr><th>Verdict</th>" +
           verdict_text(s.surface.required.of_daylight(), d.verdict.passes(), d.verdict.close()) +
           "</tr>";
    out += "</tbody></table><div class=\"plans\"><figure>" +
           surface_plan_svg(s, d.factor, {"df", "%", 0, kHalfWidth, kHalfHeight, in.north_deg},
                            nullptr, 1) +
           "<figcaption>Daylight factor on " + html_escape(s.surface.name) +
           ", seen from the side its points face; lines labelled in %" + cut_caption(s) +
           ".</figcaption></figure>";
    if (d.annual)
        out +=
            "<figure>" +
            surface_plan_svg(s, d.da300, {"da300", "%", 100, kHalfWidth, kHalfHeight, in.north_deg},
                             nullptr, 1) +
            "<figcaption>DA300 on " + html_escape(s.surface.name) +
            ": the share of occupied hours at 300 lx or more from daylight, lines labelled "
            "in %" +
            cut_caption(s) + ".</figcaption></figure>";
    out += "</div>";
    out += point_table(in, s, d.factor, "DF %", [](double v) { return fixed(v, 2); });
    return out + "</section>";
}

// A cylindrical surface's modelling index Ez/Eh: its mean over the sensors and its range.
std::string modelling_rows(const ReportSurface& s) {
    const auto m = modelling_index(s.lux, s.horizontal);
    const std::string text =
        m.count ? fixed(m.mean, 2) + " (" + fixed(m.min, 2) + " to " + fixed(m.max, 2) + ")"
                : std::string("-");
    return figure_row("Modelling Ez/Eh, mean (range)", text, "modelling") +
           "<tr><th>Light</th><td>EN 12464-1's cylindrical illuminance Ez at the surface's "
           "points about its normal (the luminaires exactly, the room's light by vertical "
           "gathers in 8 directions); Eh the horizontal illuminance at the same points. "
           "EN 12464-1 asks Ez of at least 50 lx (150 lx where faces must be seen well), U0 "
           "0.10, and a modelling index of about 0.30 to 0.60</td></tr>";
}

// A surface's illuminance plan and its caption (what is drawn on it).
std::string illuminance_figure(const ReportInput& in, const ReportSurface& s) {
    const auto& g = s.grid;
    std::string out =
        "<figure>" +
        surface_plan_svg(s, s.lux, {"lux", "lx", 0, 540, 400, in.north_deg}, in.luminaires,
                         in.metres_per_unit) +
        "<figcaption>Illuminance on " + html_escape(s.surface.name) +
        (reflected_ceiling_plan(g) ? ", a reflected ceiling plan (seen from above, the same "
                                     "way round as the floor)"
                                   : ", seen from the side its points face") +
        "; isolux lines labelled in lx";
    if (in.luminaires && horizontal_plan(g))
        out += "; luminaires over it drawn at their luminous opening's size, their centre "
               "marked";
    out += "; the scale bar in metres";
    out += cut_caption(s);
    if (std::isfinite(in.north_deg) && horizontal_plan(g)) out += "; N: north";
    out += g.border_m > 0 ? ". The grey band is the border left out." : ".";
    return out + " Grey: points without a value.</figcaption></figure>";
}

std::string surface_section(const ReportInput& in, const ReportSurface& s, std::size_t index) {
    if (s.daylight) return daylight_section(in, s, index);
    const auto& st = s.stats;
    std::string out = "<section class=\"part surface\" id=\"surface-" + std::to_string(index + 1) +
                      "\"><h2>" + html_escape(s.surface.name) + "</h2>";
    out += "<table class=\"figures\" data-surface=\"" + html_escape(s.surface.name) + "\"><tbody>";
    out += grid_rows(s);
    const auto& e = s.errors;
    const auto& r = s.surface.required;
    // EN 1838's direct light is computed exactly: no error column.
    const auto bar = [&](double error, bool ratio = false) {
        return s.grid.emergency ? std::string() : error_text(error, ratio);
    };
    // Ez or Esc, not E.
    const bool z = s.grid.cylindrical && !s.grid.semi;
    const auto name = [&](const char* plain, const char* what) {
        return !s.grid.cylindrical ? std::string(plain)
                                   : std::string(s.grid.semi ? "Esc, " : "Ez, ") + what + " (lx)";
    };
    out += figure_row(name("Em (lx)", "mean").c_str(), lux_text(st.mean, r.em), "em", bar(e.mean));
    out +=
        figure_row(name("Emin (lx)", "min").c_str(), lux_text(st.min, r.emin), "emin", bar(e.min));
    out += figure_row(name("Emax (lx)", "max").c_str(), lux_text(st.max), "emax", bar(e.max));
    out += figure_row("U0 = Emin/Em", ratio_text(st.u0(), r.u0), "u0", bar(e.u0, true));
    out += figure_row("Emin/Emax", ratio_text(st.min_over_max()), "ratio");
    if (z) out += modelling_rows(s);
    if (s.grid.semi)
        out += "<tr><th>Light</th><td>semi-cylindrical illuminance at the surface's points "
               "toward its first side (u): a small vertical half-cylinder's curved face, the "
               "luminaires exactly, the room's light by vertical gathers in 8 directions</td></tr>";
    if (s.grid.emergency) {
        out +=
            figure_row("Emax/Emin", st.min > 0 ? fixed(st.max / st.min, 1) : std::string("&#8734;"),
                       "max-over-min");
        out += "<tr><th>Light</th><td>EN 1838: the emergency luminaires' direct light only (each "
               "times its flux share on battery and its maintenance factor), no reflected "
               "light" +
               std::string(s.surface.kind == CalcKind::EscapeRoute
                               ? "; points on the route's centre line"
                               : "") +
               "</td></tr>";
    }
    if (st.without_value)
        out += "<tr><th>Points without a value</th><td>" + std::to_string(st.without_value) +
               " (inside or under objects; grey in the plan)</td></tr>";
    if (std::isfinite(s.facing_distance_m))
        out += "<tr class=\"warning\"><th>Warning</th><td>its points face a surface " +
               fixed(s.facing_distance_m, 3) +
               " m in front of them: they read the light leaving that surface, not the light "
               "falling on the place (the surface was probably given facing into a wall or "
               "ceiling: its u and v the other way round face the room)</td></tr>";
    out += "<tr><th>Required</th><td>" + required_text(s.surface.required) + "</td></tr>";
    if (!s.at_budget.empty())
        out += "<tr><th>Points short of the accuracy</th><td>" +
               std::to_string(s.at_budget.size()) + " (stopped at the ray budget)</td></tr>";
    out += "<tr><th>Verdict</th>" +
           verdict_text(s.surface.required.of_light(), s.verdict.passes(), s.verdict.close()) +
           "</tr>";
    out += "</tbody></table>" + illuminance_figure(in, s);
    out += point_table(in, s, s.lux, "lx", [](double v) { return lux_text(v); });
    return out + "</section>";
}

// How the polar curve's cd/klm of the luminaire's flux convert to what data sheets also print:
// absolute candelas, and cd/klm of the lamps' flux where the file gives the lamps.
std::string polar_units_note(const LuminaireSet& set, std::size_t index) {
    const double flux = set.photometry_flux[index];
    if (!(flux > 0)) return "";
    std::string out =
        "<br><span class=\"polar-units\">cd/klm of the luminaire's flux; absolute cd: &#215; " +
        fixed(flux / 1000, 3);
    const double lamps = set.photometries[index].lamp_lumens;
    if (lamps > 0)
        out +=
            "; of the lamps' flux (" + fixed(lamps, 0) + " lm): &#215; " + fixed(flux / lamps, 3);
    return out + "</span>";
}

// The luminaire types: photometry index -> the luminaires of it.
std::map<std::size_t, std::vector<const Luminaire*>> types_of(const LuminaireSet& set) {
    std::map<std::size_t, std::vector<const Luminaire*>> types;
    for (const auto& l : set.luminaires) types[l.photometry].push_back(&l);
    return types;
}

std::string type_name(const Photometry& p) {
    for (const char* key : {"LUMINAIRE", "LUMCAT"})
        for (const auto& [k, v] : p.keywords)
            if (k == key && !v.empty()) return v;
    return p.source;
}

// A luminaire's maintenance factor, with its parts when the layout gives them.
std::string maintenance_text(const Luminaire& l) {
    std::string text = fixed(l.maintenance, 2);
    if (!l.maintenance_parts_given) return text;
    const auto& p = l.maintenance_parts;
    return text + " = " + fixed(p[0], 2) + " &#215; " + fixed(p[1], 2) + " &#215; " +
           fixed(p[2], 2) + " &#215; " + fixed(p[3], 2);
}

// Each type's UGR table (CIE 190) as its data sheet prints it; a type whose file gives no
// luminous opening has none, and says so.
std::string ugr_tables(const LuminaireSet& set,
                       const std::map<std::size_t, std::vector<const Luminaire*>>& types) {
    // The heading and its note kept on the page of the first table.
    std::string out = "<div class=\"keep\"><h3>UGR tables (CIE 190)</h3><p class=\"note\">Each "
                      "type's Unified Glare "
                      "Rating in CIE 190's standard rooms (X across and Y along the line of sight, "
                      "in units of H, the luminaires' height above the eye), from its photometry "
                      "alone, for the lamp flux of its file; the rooms' reflectances ceiling / "
                      "walls / reference plane. CIE 117's sum over the 0.25H grid, CIE 190's "
                      "background luminance. The observers' UGR above is the room's own.</p>";
    bool first = true;
    for (const auto& [index, members] : types) {
        const auto& p = set.photometries[index];
        const std::string title = type_name(p) + " (" + p.source + ")";
        if (!(p.length > 0)) {
            out += "<p class=\"note\">" + html_escape(title) +
                   ": its file gives no luminous opening, so its luminance (and its UGR) is "
                   "undefined: no table.</p>";
            continue;
        }
        out += ugr_table_html(ugr_table(p), title) + (first ? "</div>" : "");
        first = false;
    }
    return first ? out + "</div>" : out;
}

std::string luminaires_section(const ReportInput& in) {
    const auto& set = *in.luminaires;
    const auto types = types_of(set);
    std::string out = "<section class=\"part\" id=\"luminaires\"><h2>Luminaires</h2>";
    out += "<table class=\"schedule\"><thead><tr><th>Type</th><th>File</th><th class=\"num\">"
           "Count</th><th class=\"num\">Luminaire flux (lm, each)</th><th class=\"num\">Input "
           "power (W, each)</th><th class=\"num\">Efficacy (lm/W)</th><th class=\"num\">CCT "
           "(K)</th><th>CRI</th><th class=\"num\">Maintenance factor</th><th>Luminaires</th>"
           "</tr></thead><tbody>";
    double watts = 0;
    for (const auto& [index, members] : types) {
        const auto& p = set.photometries[index];
        const double flux = set.photometry_flux[index];
        std::string names, factors;
        std::map<std::string, int> distinct;
        std::map<std::string, int> ccts;
        for (const auto* l : members) {
            names += (names.empty() ? "" : ", ") + html_escape(l->name);
            distinct[maintenance_text(*l)]++;
            ccts[l->cct > 0 ? fixed(l->cct, 0) : "-"]++;
        }
        std::string cct;
        for (const auto& [k, n] : ccts) cct += (cct.empty() ? "" : ", ") + k;
        for (const auto& [f, n] : distinct) factors += (factors.empty() ? "" : ", ") + f;
        watts += p.input_watts * double(members.size());
        out += "<tr><td>" + html_escape(type_name(p)) + "</td><td>" + html_escape(p.source) +
               "</td>" + cell(std::to_string(members.size())) + cell(fixed(flux, 0)) +
               cell(p.input_watts > 0 ? fixed(p.input_watts, 1) : "-") +
               cell(p.input_watts > 0 ? fixed(flux / p.input_watts, 1) : "-") + cell(cct) + "<td>" +
               html_escape(p.colour_rendering.empty() ? "-" : p.colour_rendering) + "</td>" +
               cell(factors) + "<td>" + names + "</td></tr>";
    }
    out += "</tbody></table>";
    out += "<p class=\"note\">Luminaire flux: the photometric file's intensities integrated over "
           "the sphere (before the maintenance factor). Input power: the file's input watts. "
           "CCT: the layout's or the file's; CRI: as the file states it. Maintenance factor: the "
           "layout's, as LLMF &#215; LSF &#215; LMF &#215; RSMF where it gives the parts.</p>";
    if (watts > 0 && in.power_area_m2 > 0)
        out += "<p class=\"power\">Installed power " + fixed(watts, 1) + " W over " +
               html_escape(in.power_area_what) + " of " + fixed(in.power_area_m2, 2) +
               " m&#178;: <b><span class=\"density\">" + fixed(watts / in.power_area_m2, 2) +
               "</span> W/m&#178;</b>.</p>";
    out += "<h3>Polar curves</h3><div class=\"polars\">";
    for (const auto& [index, members] : types)
        out += "<figure>" + polar_curve_svg(set, *members.front()) + "<figcaption>" +
               html_escape(type_name(set.photometries[index])) + " (" +
               html_escape(set.photometries[index].source) + ")" + polar_units_note(set, index) +
               "</figcaption></figure>";
    return out + "</div>" + ugr_tables(set, types) + "</section>";
}

// One input of the energy calculation: its symbol, what it is, its value, and whether the
// user gave it or it is the quick method's default.
std::string energy_row(const LightingEnergyInputs& in, const char* key, const char* symbol,
                       const std::string& what, const std::string& value) {
    bool given = false;
    for (const auto& k : in.given) given = given || k == key;
    return "<tr data-key=\"" + std::string(key) + "\"><th>" + symbol + "</th><td>" + what +
           "</td>" + cell(value) + "<td>" + (given ? "given" : "default") + "</td></tr>";
}

std::string energy_section(const LightingEnergy& e) {
    const auto& in = e.inputs;
    std::string out =
        "<section class=\"part\" id=\"energy\"><h2>Energy (EN 15193-1, LENI)"
        "</h2><p class=\"note\">The quick method: W<sub>L</sub> = P<sub>n</sub> "
        "F<sub>C</sub> (t<sub>D</sub> F<sub>O</sub> F<sub>D</sub> + t<sub>N</sub> "
        "F<sub>O</sub>) / 1000; W<sub>P</sub> = (P<sub>pc</sub> (t<sub>y</sub> &#8722; "
        "t<sub>D</sub> &#8722; t<sub>N</sub>) + P<sub>em</sub> t<sub>e</sub>) / 1000; "
        "LENI = (W<sub>L</sub> + W<sub>P</sub>) / A. Operating hours by building type "
        "as the quick method tabulates them (" +
        html_escape(in.building) + ").</p>";
    out += "<table class=\"energy-inputs\"><thead><tr><th>Symbol</th><th>Input</th><th "
           "class=\"num\">Value</th><th>Source</th></tr></thead><tbody>";
    out += "<tr data-key=\"Pn\"><th>P<sub>n</sub></th><td>installed lighting power (W): the "
           "photometric files' input watts</td>" +
           cell(fixed(e.lighting_watts, 1)) + "<td>layout</td></tr>";
    out += "<tr data-key=\"A\"><th>A</th><td>floor area (m&#178;)</td>" +
           cell(fixed(e.area_m2, 2)) + "<td>as the power density</td></tr>";
    out += energy_row(in, "tD", "t<sub>D</sub>", "operating hours with daylight (h/a)",
                      fixed(in.daylight_hours, 0));
    out += energy_row(in, "tN", "t<sub>N</sub>", "operating hours without daylight (h/a)",
                      fixed(in.night_hours, 0));
    out += energy_row(in, "FC", "F<sub>C</sub>", "constant illuminance factor",
                      fixed(in.constant_illuminance, 2));
    out += energy_row(in, "FO", "F<sub>O</sub>", "occupancy dependency factor",
                      fixed(in.occupancy, 2));
    out +=
        energy_row(in, "FD", "F<sub>D</sub>", "daylight dependency factor", fixed(in.daylight, 2));
    out += energy_row(in, "Ppc", "P<sub>pc</sub>", "controls' standby power (W)",
                      fixed(in.controls_watts, 1));
    out += energy_row(in, "Pem", "P<sub>em</sub>", "emergency charging power (W)",
                      fixed(in.emergency_watts, 1));
    out += energy_row(in, "te", "t<sub>e</sub>", "emergency charging hours (h/a)",
                      fixed(in.charge_hours, 0));
    out += "</tbody></table><table class=\"energy\"><tbody>";
    out += "<tr><th>W<sub>L</sub>, lighting (kWh/a)</th>" +
           cell("<span class=\"wl\">" + fixed(e.lighting_kwh, 1) + "</span>") + "</tr>";
    out += "<tr><th>W<sub>P</sub>, parasitic (kWh/a)</th>" +
           cell("<span class=\"wp\">" + fixed(e.parasitic_kwh, 1) + "</span>") + "</tr>";
    out += "<tr><th>W, total (kWh/a)</th>" + cell(fixed(e.total_kwh(), 1)) + "</tr>";
    out += "<tr><th>LENI (kWh/(m&#178;&#183;a))</th>" +
           cell("<b><span class=\"leni\">" + fixed(e.leni(), 2) + "</span></b>") + "</tr>";
    return out + "</tbody></table></section>";
}

std::string glare_section(const ReportInput& in) {
    std::string out = "<section class=\"part\" id=\"glare\"><h2>Glare (UGR)</h2>";
    out += "<p class=\"note\">CIE 117: UGR = 8 log<sub>10</sub>(0.25/L<sub>b</sub> &#183; "
           "&#931; L&#178;&#969;/p&#178;). L: a luminaire's luminance toward the eye (its "
           "maintained intensity over its luminous opening's projected area, from the "
           "photometric file); &#969;: that area's solid angle; p: Guth's position index; "
           "L<sub>b</sub>: the illuminance at the eye from the room's surfaces (the solution, "
           "luminaires' direct light excluded) over &#960;. Luminaires behind the eye, below "
           "the line of sight or hidden do not count. The position index p is Guth's (the IES "
           "fit of Luckiesh and Guth's table), over that table's extent as CIE 117 uses it: a "
           "luminaire higher above the line of sight than 1.9 times its distance along it "
           "(H/R), or farther to the side than 3 times (T/R), is left out and named, not "
           "given a capped p.</p>";
    for (const auto& o : in.observers) {
        const auto& ob = o.observer;
        out += "<h3>" + html_escape(ob.name) + "</h3><table class=\"observer\" data-observer=\"" +
               html_escape(ob.name) + "\"><tbody>";
        out += "<tr><th>Eye</th><td>(" + fixed(ob.position[0], 2) + ", " +
               fixed(ob.position[1], 2) + ", " + fixed(ob.position[2], 2) + "), looking (" +
               fixed(ob.view[0], 2) + ", " + fixed(ob.view[1], 2) + ", " + fixed(ob.view[2], 2) +
               ")</td></tr>";
        out += "<tr><th>Background L<sub>b</sub> (cd/m&#178;)</th><td class=\"num\">" +
               fixed(o.background, 2) + "</td></tr>";
        out += "<tr><th>UGR</th><td class=\"num ugr\">" + ugr_text(o.glare.ugr) + "</td></tr>";
        out += "<tr><th>Luminaires counted</th><td>" + std::to_string(o.glare.terms.size()) +
               " (behind or below the line of sight " + std::to_string(o.glare.behind_or_below) +
               ", hidden " + std::to_string(o.glare.hidden) + ", no luminous area " +
               std::to_string(o.glare.pointlike) + ", outside the position-index table " +
               std::to_string(o.glare.outside_table.size()) + ")</td></tr>";
        if (!o.glare.outside_table.empty()) {
            std::string names;
            for (const auto k : o.glare.outside_table)
                names +=
                    (names.empty() ? "" : ", ") + html_escape(in.luminaires->luminaires[k].name);
            out += "<tr><th>Left out (CIE 117)</th><td class=\"outside-table\">" + names +
                   "</td></tr>";
        }
        out += "</tbody></table>";
        if (o.glare.terms.empty()) continue;
        out += "<table class=\"terms\"><thead><tr><th>Luminaire</th><th class=\"num\">L "
               "(cd/m&#178;)</th><th class=\"num\">&#969; (sr)</th><th class=\"num\">&#963; "
               "(&#176;)</th><th class=\"num\">&#964; (&#176;)</th><th class=\"num\">p</th>"
               "</tr></thead><tbody>";
        for (const auto& t : o.glare.terms) {
            char omega[32];
            std::snprintf(omega, sizeof omega, "%.3e", t.solid_angle);
            out += "<tr><td>" + html_escape(in.luminaires->luminaires[t.luminaire].name) + "</td>" +
                   cell(fixed(t.luminance, 0)) + cell(omega) + cell(fixed(t.sigma_deg, 1)) +
                   cell(fixed(t.tau_deg, 1)) + cell(fixed(t.position_index, 2)) + "</tr>";
        }
        out += "</tbody></table>";
    }
    return out + "</section>";
}

// A view's luminance: the false-colour picture and each surface's figures.
std::string view_luminance(const ReportView& v) {
    std::string out =
        "<figure class=\"view luminance\" data-view=\"" + html_escape(v.name) +
        "\"><img alt=\"luminance of " + html_escape(v.name) + "\" src=\"data:image/png;base64," +
        base64(v.falsecolor_png) + "\"><figcaption>Luminance (cd/m&#178;) of " +
        html_escape(v.name) + ", logarithmic from " + short_number(v.scale.bottom()) + " to " +
        short_number(v.scale.top) + " cd/m&#178;; black: nothing seen.</figcaption></figure>";
    out += "<table class=\"luminances\" data-view=\"" + html_escape(v.name) +
           "\"><thead><tr><th>Surface seen</th><th class=\"num\">Share of the view</th><th "
           "class=\"num\">Mean (cd/m&#178;)</th><th class=\"num\">Max (cd/m&#178;)</th></tr>"
           "</thead><tbody>";
    const double pixels = double(v.width) * v.height;
    for (const auto& s : v.surfaces)
        out += "<tr><td>" + html_escape(s.name) + "</td>" +
               cell(fixed(100 * double(s.pixels) / pixels, 1) + "%") + cell(lux_text(s.mean)) +
               cell(lux_text(s.max)) + "</tr>";
    return out + "</tbody></table>";
}

std::string views_section(const ReportInput& in) {
    std::string out = "<section class=\"part\" id=\"views\"><h2>Views</h2>";
    for (const auto& v : in.views)
        out += "<figure class=\"view\" data-view=\"" + html_escape(v.name) + "\"><img alt=\"" +
               html_escape(v.name) + "\" width=\"" + std::to_string(v.width) + "\" height=\"" +
               std::to_string(v.height) + "\" src=\"data:image/png;base64," + base64(v.png) +
               "\"><figcaption>" + html_escape(v.name) +
               ": the final gather over the solution, as <code class=\"command\">" +
               html_escape(v.command) + "</code> renders it.</figcaption></figure>" +
               view_luminance(v);
    return out + "</section>";
}

std::string method_section(const ReportInput& in) {
    return "<section id=\"method\"><h2>Method</h2><p>" + html_escape(in.method) +
           "</p><p>Calculation grids follow EN 12464-1: points at the centres of cells of at most "
           "p = 0.2 &#215; 5<sup>log<sub>10</sub> d</sup> m (d: the calculation area's longer "
           "side; at most 10 m) unless the file gives a spacing, a work plane's 0.5 m border "
           "band left out unless the file gives another. The values on this page are the ones "
           "<code>rad-gather --surfaces</code> writes for the same inputs.</p></section>";
}

} // namespace

std::string lux_text(double lux) {
    if (!std::isfinite(lux)) return "-";
    const double a = std::abs(lux);
    return fixed(lux, a >= 99.95 ? 0 : a >= 9.995 ? 1 : 2);
}

std::string ratio_text(double ratio) {
    return std::isfinite(ratio) ? fixed(ratio, 2) : "-";
}

namespace {
// `value` to `decimals`, or more until the printed number compares with `required` as the
// value does.
std::string agreeing(double value, double required, int decimals) {
    std::string text = fixed(value, decimals);
    if (!std::isfinite(value) || !std::isfinite(required)) return text;
    const bool meets = value >= required;
    for (int d = decimals; d <= decimals + 4; ++d) {
        text = fixed(value, d);
        if ((std::strtod(text.c_str(), nullptr) >= required) == meets) break;
    }
    return text;
}
} // namespace

std::string lux_text(double lux, double required) {
    if (!std::isfinite(lux)) return "-";
    const double a = std::abs(lux);
    return agreeing(lux, required, a >= 99.95 ? 0 : a >= 9.995 ? 1 : 2);
}

std::string ratio_text(double ratio, double required) {
    return std::isfinite(ratio) ? agreeing(ratio, required, 2) : "-";
}

std::string html_escape(const std::string& text) {
    std::string out;
    for (const char c : text) switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    return out;
}

std::string daylight_glare_section(const ReportInput& in) {
    std::string out = "<section class=\"part\" id=\"daylight-glare\"><h2>Daylight glare "
                      "(DGP)</h2>";
    out += "<p class=\"note\">The daylight glare probability (Wienold and Christoffersen 2006) "
           "at each observer's eye for every occupied hour of " +
           html_escape(in.weather) +
           ", as Radiance's evalglare computes it from a fisheye picture: the vertical "
           "illuminance E<sub>v</sub> and the glare sources (over 2000 cd/m&#178;, joined "
           "within 0.2 rad), DGP = 5.87&#183;10<sup>-5</sup> E<sub>v</sub> + 0.092 "
           "log<sub>10</sub>(1 + &#931; L&#178;&#969;/(E<sub>v</sub><sup>1.87</sup> "
           "p&#178;)) + 0.159, with the low-light correction below 1000 lx. EN 17037 (annex "
           "A.5): protection from glare is high, medium or minimum where DGP exceeds 0.35, "
           "0.40 or 0.45 in no more than 5% of the occupied hours.</p>";
    out += "<table class=\"daylight-glare\"><thead><tr><th>Observer</th><th>Eye, looking</th>"
           "<th class=\"num\">Hours</th><th class=\"num\">DGP &gt; 0.35</th>"
           "<th class=\"num\">DGP &gt; 0.40</th><th class=\"num\">DGP &gt; 0.45</th>"
           "<th class=\"num\">Mean DGP</th><th>EN 17037</th></tr></thead><tbody>";
    const auto percent = [](double share) { return fixed(100 * share, 1) + "%"; };
    for (const auto& g : in.daylight_glare) {
        const auto& o = g.observer;
        out += "<tr data-observer=\"" + html_escape(o.name) + "\"><td>" + html_escape(o.name) +
               "</td><td>(" + fixed(o.position[0], 2) + ", " + fixed(o.position[1], 2) + ", " +
               fixed(o.position[2], 2) + "), (" + fixed(o.view[0], 2) + ", " + fixed(o.view[1], 2) +
               ", " + fixed(o.view[2], 2) + ")</td><td class=\"num\">" +
               std::to_string(g.year.hours) + "</td><td class=\"num\">" + percent(g.year.over_035) +
               "</td><td class=\"num\">" + percent(g.year.over_040) + "</td><td class=\"num\">" +
               percent(g.year.over_045) + "</td><td class=\"num\">" + fixed(g.year.mean, 3) +
               "</td><td class=\"en17037-glare\">" + g.year.en17037() + "</td></tr>";
    }
    return out + "</tbody></table></section>";
}

std::string report_html(const ReportInput& in) {
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                      "<meta name=\"viewport\" content=\"width=device-width\"><title>" +
                      report_kind(in) + ": " + html_escape(in.project) + "</title><style>" +
                      kStyle + "</style></head><body>\n";
    out += title_block(in) + "\n" + contents(in) + "\n" + summary(in) + "\n";
    if (in.room) out += room_section(in) + "\n";
    for (std::size_t k = 0; k < in.surfaces.size(); ++k)
        out += surface_section(in, in.surfaces[k], k) + "\n";
    if (in.luminaires) out += luminaires_section(in) + "\n";
    if (in.energy) out += energy_section(*in.energy) + "\n";
    if (!in.observers.empty()) out += glare_section(in) + "\n";
    if (!in.daylight_glare.empty()) out += daylight_glare_section(in) + "\n";
    if (!in.views.empty()) out += views_section(in) + "\n";
    out += method_section(in) + "\n</body></html>\n";
    return out;
}

} // namespace rad
