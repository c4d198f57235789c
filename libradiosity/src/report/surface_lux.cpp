// Illuminance at every sensor of the calculation surfaces, in parallel, deterministic.
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/progress.hpp"

#include <tbb/parallel_for.h>

namespace rad {

std::vector<std::vector<double>>
gather_surfaces(const Gatherer& gatherer, const LuminaireSet* luminaires, const Box& scene_box,
                const std::vector<SurfaceGrid>& grids, bool quiet) {
    std::uint64_t total = 0;
    for (const auto& grid : grids) total += std::uint64_t(grid.size());
    Progress progress("sensors", total, quiet);
    std::vector<std::vector<double>> lux;
    std::uint64_t first = 0; // the first sensor's index over all surfaces
    for (const auto& grid : grids) {
        auto& values = lux.emplace_back(std::size_t(grid.size()));
        tbb::parallel_for(long(0), grid.size(), [&](long k) {
            std::string problem;
            const auto result = gather_sensor(gatherer, luminaires, scene_box, grid.position(k),
                                              grid.normal, first + std::uint64_t(k), problem);
            values[std::size_t(k)] = problem.empty() ? rad::lux(result.total())
                                                     : std::numeric_limits<double>::quiet_NaN();
            progress.advance(1);
        });
        first += std::uint64_t(grid.size());
    }
    progress.finish();
    return lux;
}

} // namespace rad
