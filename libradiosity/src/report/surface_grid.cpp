// A calculation surface's sensors by EN 12464-1's rule, and the verdict on its figures.
#include "radiosity/calc_surfaces.hpp"

#include <algorithm>
#include <cmath>

namespace rad {

double en12464_spacing(double longer_m) {
    return std::min(10.0, 0.2 * std::pow(5.0, std::log10(longer_m)));
}

SurfaceGrid surface_grid(const CalcSurface& surface, double metres_per_unit) {
    SurfaceGrid grid;
    const double length_u = length(surface.u) * metres_per_unit;
    const double length_v = length(surface.v) * metres_per_unit;
    const bool route = surface.kind == CalcKind::EscapeRoute;
    const bool semi = surface.kind == CalcKind::SemiCylindrical;
    const bool banded = surface.kind == CalcKind::WorkPlane || surface.kind == CalcKind::OpenArea ||
                        surface.kind == CalcKind::Cylindrical || semi;
    grid.border_m = std::isnan(surface.border_m) ? (banded ? 0.5 : 0.0) : surface.border_m;
    grid.emergency = is_emergency(surface.kind);
    grid.cylindrical = surface.kind == CalcKind::Cylindrical || semi;
    grid.semi = semi;
    grid.where = surface.where;
    grid.width_m = length_u - 2 * grid.border_m;
    grid.depth_m = route ? length_v : length_v - 2 * grid.border_m; // a route's width stays
    if (!(grid.width_m > 0) || !(grid.depth_m > 0))
        throw InputError(surface.where,
                         "the border band of " + std::to_string(grid.border_m) +
                             " m leaves no area of the surface (a work plane's default is "
                             "EN 12464-1's 0.5 m): give a smaller border, e.g. 0");
    const double rule = en12464_spacing(std::max(grid.width_m, grid.depth_m));
    grid.spacing_m = surface.spacing_m > 0 ? surface.spacing_m
                     : grid.emergency      ? std::min(rule, kEmergencySpacing)
                                           : rule;
    const double columns = std::ceil(grid.width_m / grid.spacing_m - 1e-9);
    const double rows = route ? 1.0 : std::ceil(grid.depth_m / grid.spacing_m - 1e-9);
    if (columns * rows > 1e6)
        throw InputError(surface.where, "a spacing of " + std::to_string(grid.spacing_m) +
                                            " m makes over a million sensors: give a larger one");
    grid.columns = std::max(1L, long(columns));
    grid.rows = std::max(1L, long(rows));
    const Vec3 unit_u = normalized(surface.u), unit_v = normalized(surface.v);
    const double border = grid.border_m / metres_per_unit;
    grid.origin = surface.corner + unit_u * border + unit_v * (route ? 0.0 : border);
    grid.column_step = unit_u * (grid.width_m / metres_per_unit / double(grid.columns));
    grid.row_step = unit_v * (grid.depth_m / metres_per_unit / double(grid.rows));
    grid.normal = normalized(cross(surface.u, surface.v));
    // A semi-cylinder faces along u, level (u less its part along the normal).
    const Vec3 level = surface.u - grid.normal * dot(surface.u, grid.normal);
    if (length(level) > 0) grid.facing = normalized(level);
    return grid;
}

ModellingIndex modelling_index(const std::vector<double>& cylindrical,
                               const std::vector<double>& horizontal) {
    ModellingIndex m;
    double sum = 0;
    for (std::size_t k = 0; k < cylindrical.size() && k < horizontal.size(); ++k) {
        if (!std::isfinite(cylindrical[k]) || !(horizontal[k] > 0)) continue;
        const double ratio = cylindrical[k] / horizontal[k];
        m.min = m.count ? std::min(m.min, ratio) : ratio;
        m.max = m.count ? std::max(m.max, ratio) : ratio;
        sum += ratio;
        ++m.count;
    }
    if (m.count) m.mean = sum / double(m.count);
    return m;
}

void refuse_daylight_unsupported(const CalcFile& file) {
    for (const auto& s : file.surfaces)
        if (is_emergency(s.kind))
            throw InputError(s.where, std::string("an ") + calc_kind_name(s.kind) +
                                          " is lit by emergency luminaires (EN 1838), and a "
                                          "daylight solution has none: report it on the "
                                          "luminaires' solution, or remove the line");
        else if (s.kind == CalcKind::Cylindrical || s.kind == CalcKind::SemiCylindrical)
            throw InputError(s.where, std::string("a ") + calc_kind_name(s.kind) +
                                          " surface's daylight is not computed yet (its "
                                          "sensors would give the horizontal daylight factor): "
                                          "report it on a luminaires' solution, or remove the "
                                          "line");
}

std::vector<SurfaceGrid> surface_grids(const CalcFile& file, double metres_per_unit) {
    std::vector<SurfaceGrid> grids;
    for (const auto& surface : file.surfaces)
        grids.push_back(surface_grid(surface, metres_per_unit));
    return grids;
}

void surface_sensors(const CalcFile& file, const std::vector<SurfaceGrid>& grids, const Box& box,
                     std::vector<Vec3>& positions, std::vector<Vec3>& normals) {
    for (std::size_t s = 0; s < grids.size(); ++s)
        for (long k = 0; k < grids[s].size(); ++k) {
            positions.push_back(grids[s].position(k));
            if (const auto why = out_of_reach(positions.back(), box); !why.empty())
                throw InputError(file.surfaces[s].where,
                                 file.surfaces[s].name + "'s sensors: " + why);
            normals.push_back(grids[s].normal);
        }
}

Verdict judge(const IlluminanceStats& stats, const Requirements& required,
              const IlluminanceErrors& errors) {
    Verdict v;
    if (stats.count == 0) {
        v.em = std::isnan(required.em), v.u0 = std::isnan(required.u0);
        v.emin = std::isnan(required.emin);
        v.max_over_min = std::isnan(required.max_over_min);
        return v;
    }
    const auto em = judge_figure(stats.mean, errors.mean, required.em);
    const auto u0 = judge_figure(stats.u0(), errors.u0, required.u0);
    const auto emin = judge_figure(stats.min, errors.min, required.emin);
    v.em = em.passes, v.em_close = em.close;
    v.u0 = u0.passes, v.u0_close = u0.close;
    v.emin = emin.passes, v.emin_close = emin.close;
    // Emax/Emin at most the limit (a minimum of 0 never meets it).
    if (!std::isnan(required.max_over_min))
        v.max_over_min = stats.min > 0 && stats.max <= required.max_over_min * stats.min;
    return v;
}

DaylightVerdict judge_daylight(double mean_df, const double* sda, const double* ase,
                               const Requirements& required, double mean_df_error,
                               double sda_error) {
    DaylightVerdict v;
    const auto df = judge_figure(mean_df, mean_df_error, required.df);
    v.df = df.passes, v.df_close = df.close;
    if (!std::isnan(required.sda) && sda) {
        const auto judged = judge_figure(100 * *sda, 100 * sda_error, required.sda);
        v.sda = judged.passes, v.sda_close = judged.close;
    }
    if (!std::isnan(required.ase) && ase) v.ase = 100 * *ase <= required.ase;
    return v;
}

} // namespace rad
