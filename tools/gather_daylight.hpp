// rad-gather's daylight: a sky at an instant (--sky, --daylight-factor) or a year from a
// weather file (--epw --annual), at the sensors of a solution solved with a .sky.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/vec.hpp"
#include "radiosity/weather.hpp"
#include "tool.hpp"

#include <CLI/CLI.hpp>

#include <limits>
#include <string>
#include <vector>

namespace rad::tool {

// The room's reflected light at a sensor: rays unless --rays says (the reflected light of
// every sky patch comes from them, and a year's thresholds are sharp).
inline constexpr int kDaylightRays = 1024;

struct DaylightArgs {
    SkyChoice choice;
    std::string epw, occupancy, metrics;
    // --shaded MESH RADIOSITY: the window's shaded state; --shading-rule, -group and -log.
    std::vector<std::string> shaded;
    std::string shading_rule = "lm83", shading_group, shading_log;
    // --glare "x y z dx dy dz" (repeatable), --glare-threshold, --glare-no-low-light.
    std::vector<std::string> glare;
    std::string glare_hours; // --annual --glare: every hour's DGP as CSV
    // --sunlight-exposure "x y z" (repeatable) above --sun-min-altitude degrees.
    std::vector<std::string> sunlight;
    double sun_min_altitude = std::numeric_limits<double>::quiet_NaN();
    double glare_threshold = 2000;
    bool glare_no_low_light = false;
    bool daylight_factor = false, annual = false;
    int sky_samples = 64;
};
void add_daylight_options(CLI::App& app, DaylightArgs& a);
bool wants_daylight(const DaylightArgs& a);

// What rad-gather's common options give the daylight run.
struct DaylightRun {
    const radfmt::MeshData* mesh = nullptr;
    const radfmt::RadiosityData* solution = nullptr;
    const radfmt::Header* rad_header = nullptr;
    std::string rad_path, output, png, header_line;
    std::string direct_path;         // --direct: the .sky when it has moved
    std::vector<std::string> inputs; // for the .ill's provenance
    std::string command;
    std::vector<Vec3> positions, normals;
    int grid_columns = 0, grid_rows = 0; // a --grid's, for --png; 0: points
    // --surfaces: each sensor's "surface,index,column,row" (the output is CSV), and each
    // surface's name and sensor count, in order.
    std::vector<std::string> labels;
    std::vector<std::pair<std::string, std::size_t>> surfaces;
    std::vector<bool> reference_planes; // per surface: a work plane (EN 17037's plane)
    int rays = kDaylightRays;
    double accuracy = 0; // rounds of the reflected light's rays to this relative error
    int max_rays = 4096;
    std::uint64_t seed = 1;
    bool quiet = false;
    bool error = false; // --error: each value's standard error beside it
    // --melanopic (under one sky): melanopic EDI beside lux, the sky of spectrum `spectra`
    // (one SPEC; D65 when empty).
    bool melanopic = false;
    std::vector<std::string> spectra;
    double lux_max = 0;
};
int gather_daylight(const DaylightArgs& a, const DaylightRun& run);
// --glare (DGP at views) and --sunlight-exposure (at reference points): no sensors needed.
bool wants_glare(const DaylightArgs& a);

// What a command line makes of the sensors' daylight (rad-gather, rad-report): --sky-samples
// rounded to a square, the room's reflected light's rays, the seed, and --accuracy's rounds
// (of at most --max-rays, or `rays` when more).
DaylightOptions daylight_options(int sky_samples, int rays, std::uint64_t seed, double accuracy = 0,
                                 int max_rays = 4096);
// The occupied hours: --occupancy's file, or LM-83's default (empty `occupancy`); and how a
// summary or a page names them.
std::vector<std::uint8_t> occupied_hours(const std::string& occupancy, const Weather& weather);
std::string occupancy_text(const std::string& occupancy);

} // namespace rad::tool
