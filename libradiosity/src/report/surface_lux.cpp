// Illuminance at every sensor of the calculation surfaces, in parallel, deterministic.
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/cylindrical.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/progress.hpp"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>

namespace rad {
namespace {

// EN 1838's illuminance: the emergency luminaires' direct light (each times its share on
// battery; maintenance included), no reflected light.
double emergency_lux(const Gatherer& gatherer, const LuminaireSet& set, const Vec3& point,
                     const Vec3& normal) {
    double lux = 0;
    for (const auto& l : set.luminaires)
        if (l.emergency > 0)
            lux += l.emergency * luminaire_illuminance(set, l, point, normal, &gatherer.scene(),
                                                       {&gatherer.specular(), &gatherer.mirrors()});
    return lux;
}

void check_emergency_luminaires(const SurfaceGrid& grid, const LuminaireSet* set) {
    if (set)
        for (const auto& l : set->luminaires)
            if (l.emergency > 0) return;
    throw InputError(grid.where, "an escape route or open area is lit by emergency luminaires "
                                 "(EN 1838), and the solution's layout marks none: give the "
                                 "layout an 'emergency' column (each emergency luminaire's flux "
                                 "share on battery, e.g. 0.1)");
}

struct SensorContext {
    const Gatherer& gatherer;
    const LuminaireSet* luminaires;
    const Box& box;
    const SurfaceGrid& grid;
    std::uint64_t first; // the grid's first sensor's index over all surfaces
};

// Sensor k's value (and error; a cylindrical grid's Eh) by its grid's kind, left NaN where it
// has none; whether it stopped at the ray budget.
bool sensor_value(const SensorContext& c, long k, GatheredSurface& surface) {
    const auto i = std::size_t(k);
    const auto position = c.grid.position(k);
    const auto index = c.first + std::uint64_t(k);
    std::string problem;
    if (c.grid.emergency) {
        if (!out_of_reach(position, c.box).empty()) return false;
        surface.lux[i] = emergency_lux(c.gatherer, *c.luminaires, position, c.grid.normal);
        surface.error[i] = 0;
        return false;
    }
    if (c.grid.cylindrical) {
        const auto z =
            cylindrical_illuminance(c.gatherer, c.luminaires, c.box, position, c.grid.normal, index,
                                    problem, c.grid.semi ? &c.grid.facing : nullptr);
        if (!problem.empty()) return false;
        surface.lux[i] = c.grid.semi ? z.semi_cylindrical : z.cylindrical;
        surface.error[i] = c.grid.semi ? z.semi_error : z.error;
        surface.horizontal[i] = z.horizontal;
        return z.at_budget;
    }
    const auto result =
        gather_sensor(c.gatherer, c.luminaires, c.box, position, c.grid.normal, index, problem);
    if (!problem.empty()) return false;
    surface.lux[i] = rad::lux(result.total());
    surface.error[i] = kRadianceEfficacy * result.luminous_error;
    return result.at_budget;
}

} // namespace

double facing_surface_distance(const RayScene& scene, const SurfaceGrid& grid) {
    if (grid.columns <= 0 || grid.rows <= 0) return std::numeric_limits<double>::quiet_NaN();
    // Metres per scene unit, from a cell's size in both.
    const double cell = length(grid.column_step);
    const double metres = cell > 0 ? grid.width_m / double(grid.columns) / cell : 1;
    std::vector<double> near;
    int traced = 0;
    for (const long row : {0L, grid.rows / 2, grid.rows - 1})
        for (const long column : {0L, grid.columns / 2, grid.columns - 1}) {
            ++traced;
            const auto hit = scene.trace(grid.position(row * grid.columns + column), grid.normal);
            const double d = hit.distance * metres;
            if (hit.patch >= 0 && hit.front && d < kFacingTooClose) near.push_back(d);
        }
    if (2 * near.size() <= std::size_t(traced)) return std::numeric_limits<double>::quiet_NaN();
    std::nth_element(near.begin(), near.begin() + std::ptrdiff_t(near.size() / 2), near.end());
    return near[near.size() / 2];
}

std::vector<GatheredSurface> gather_surfaces(const Gatherer& gatherer,
                                             const LuminaireSet* luminaires, const Box& scene_box,
                                             const std::vector<SurfaceGrid>& grids, bool quiet,
                                             const SensorsEstimated& estimated) {
    std::uint64_t total = 0;
    for (const auto& grid : grids) total += std::uint64_t(grid.size());
    Progress progress("sensors", total, quiet);
    std::vector<GatheredSurface> out;
    std::uint64_t first = 0; // the first sensor's index over all surfaces
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    // The first kEstimateSensors sensors are timed on their own; the whole run's time is
    // projected from them and handed to `estimated`, which may stop the run there.
    const auto start = std::chrono::steady_clock::now();
    std::uint64_t measured = 0;
    bool told = !estimated;
    for (const auto& grid : grids) {
        auto& surface = out.emplace_back();
        surface.lux.assign(std::size_t(grid.size()), kNone);
        surface.error.assign(std::size_t(grid.size()), kNone);
        if (grid.cylindrical) surface.horizontal.assign(std::size_t(grid.size()), kNone);
        std::vector<std::uint8_t> stopped(std::size_t(grid.size()), 0);
        if (grid.emergency) check_emergency_luminaires(grid, luminaires);
        const SensorContext context{gatherer, luminaires, scene_box, grid, first};
        const auto compute = [&](long from, long to) {
            tbb::parallel_for(from, to, [&](long k) {
                stopped[std::size_t(k)] = sensor_value(context, k, surface);
                progress.advance(1);
            });
        };
        long done = 0;
        if (!told) {
            done = long(
                std::min<std::uint64_t>(std::uint64_t(grid.size()), kEstimateSensors - measured));
            compute(0, done);
            measured += std::uint64_t(done);
            if (measured >= std::min<std::uint64_t>(kEstimateSensors, total)) {
                told = true;
                const double seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                const auto threads = static_cast<unsigned>(tbb::global_control::active_value(
                    tbb::global_control::max_allowed_parallelism));
                if (!estimated({seconds * double(total) / double(measured), total, measured,
                                grids.size(), threads})) {
                    progress.finish();
                    return out;
                }
            }
        }
        compute(done, grid.size());
        for (long k = 0; k < grid.size(); ++k)
            if (stopped[std::size_t(k)]) surface.at_budget.push_back(k);
        surface.facing_distance_m = facing_surface_distance(gatherer.scene(), grid);
        first += std::uint64_t(grid.size());
    }
    progress.finish();
    return out;
}

} // namespace rad
