// Illuminance at every sensor of the calculation surfaces, in parallel, deterministic.
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/progress.hpp"

#include <tbb/parallel_for.h>

#include <cstdint>
#include <limits>

namespace rad {

std::vector<GatheredSurface> gather_surfaces(const Gatherer& gatherer,
                                             const LuminaireSet* luminaires, const Box& scene_box,
                                             const std::vector<SurfaceGrid>& grids, bool quiet) {
    std::uint64_t total = 0;
    for (const auto& grid : grids) total += std::uint64_t(grid.size());
    Progress progress("sensors", total, quiet);
    std::vector<GatheredSurface> out;
    std::uint64_t first = 0; // the first sensor's index over all surfaces
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    for (const auto& grid : grids) {
        auto& surface = out.emplace_back();
        surface.lux.assign(std::size_t(grid.size()), kNone);
        surface.error.assign(std::size_t(grid.size()), kNone);
        std::vector<std::uint8_t> stopped(std::size_t(grid.size()), 0);
        tbb::parallel_for(long(0), grid.size(), [&](long k) {
            std::string problem;
            const auto result = gather_sensor(gatherer, luminaires, scene_box, grid.position(k),
                                              grid.normal, first + std::uint64_t(k), problem);
            if (problem.empty()) {
                const auto i = std::size_t(k);
                surface.lux[i] = rad::lux(result.total());
                surface.error[i] = kRadianceEfficacy * result.luminous_error;
                stopped[i] = result.at_budget;
            }
            progress.advance(1);
        });
        for (long k = 0; k < grid.size(); ++k)
            if (stopped[std::size_t(k)]) surface.at_budget.push_back(k);
        first += std::uint64_t(grid.size());
    }
    progress.finish();
    return out;
}

} // namespace rad
