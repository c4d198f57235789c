// Daylight coefficients: how much each sky patch (and the ground) lights each mesh patch and
// each sensor, per unit of its luminance, through openings and glass. Computed once from the
// geometry (rad-ff --sky, the .sky file), solved as one light group per sky patch (rad-solve
// --direct), then any sky or any hour of a year is a weighted sum (rad-gather).
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/sky_patches.hpp"
#include "radiosity/spectrum.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/weather.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rad {

struct SkyViewOptions {
    SkyPatches patches;
    SkyFrame frame;
    int rays = 1000;        // per mesh patch: cosine-weighted, quasi-Monte Carlo
    std::uint64_t seed = 1; // each patch's own stream
    int specular_depth = kDefaultSpecularDepth;
};

// Per mesh patch i in [begin, end) and sky patch s, D_is (RGB): the irradiance on i's front
// from s at unit radiance, the integral over s of visibility x glass's transmittance x cos,
// estimated by `rays` cosine-weighted rays from points over i (pi / rays per ray that leaves
// the scene into s). Patch-major: out[(i - begin) * count + s]. Deterministic.
struct SkyViewStats {
    std::uint64_t rays = 0, escaped = 0;
    double seconds = 0;
};
std::vector<radfmt::Rgb> patch_sky_view(const radfmt::MeshData& mesh, const RayScene& scene,
                                        const SpecularSurfaces& specular,
                                        const SkyViewOptions& options, std::uint64_t begin,
                                        std::uint64_t end, SkyViewStats* stats = nullptr,
                                        bool quiet = true);

// Joins .sky parts (rad-ff --sky --rows) of one mesh and options into the .sky one run would
// have written to `output`, byte for byte; every row exactly once (InputError naming a gap, an
// overlap or a part of other inputs). Returns the rows merged.
std::uint64_t merge_sky_parts(const std::vector<std::string>& paths, const std::string& output);

// Where a sensor's view of the sky is sampled finer: each sky patch's cells at a finer side,
// and each patch's neighbours (patches whose directions border on its own).
struct SkyRefinement {
    SkyPatches::Cells fine;
    std::vector<std::vector<std::uint32_t>> neighbours;
    SkyFrame frame;    // the frame the cells were made in
    int fine_side = 0; // the fine cells' side
    bool empty() const { return fine.empty(); }
};
// The refinement for `cells` at `side` (see sensor_sky_paths): 3 times the side, at most 32;
// empty when side is 32 or more.
SkyRefinement sky_refinement(const SkyPatches& patches, const SkyFrame& frame,
                             const SkyPatches::Cells& cells, int side);

// What a sensor sees of the sky directly: every sky patch (and the ground) sampled by its
// `cells` (SkyPatches::cells: directions of equal solid angle), each followed through mirrors
// and glass; a SkyPath for each path that leaves the scene, weight = the path's RGB x its
// cell's solid angle x cos to `normal`. Directions behind the sensor are skipped. Where an
// opening's edge may cross a patch (some of its directions leave the scene and some do not,
// or a neighbour's do otherwise than its own), the patch is sampled again by `refine`'s finer
// cells instead, when given: the sky's direct part is resolved where it changes, not
// everywhere.
// With `jitter` too, a refined patch's fine cells where the edge runs (a cell whose centre
// leaves the scene where a neighbour's does not, or the other way) are sampled unbiasedly
// instead of at their centre: split 2 x 2, each part at two directions drawn uniformly in it
// (each path at half the part's weight), slot 2 x part + pass (parts numbered from 0 in the
// order they come); the rest keep their centres (slot -1). The caller estimates the
// quadrature's variance from the two passes (SkyQuadratureVariance).
struct SkyPath {
    Vec3 direction;
    radfmt::Rgb weight;
    std::int64_t slot;
};
// The paths in order, patch by patch; valid until this thread's next call.
const std::vector<SkyPath>&
sensor_sky_path_list(const RayScene& scene, const SpecularSurfaces& specular,
                     const SkyPatches& patches, const SkyPatches::Cells& cells, int depth,
                     const Vec3& point, const Vec3& normal, const SkyRefinement* refine = nullptr,
                     Rng* jitter = nullptr);
// The same handed to escape(direction, weight, slot), in order.
template <class Escape>
void sensor_sky_paths(const RayScene& scene, const SpecularSurfaces& specular,
                      const SkyPatches& patches, const SkyPatches::Cells& cells, int depth,
                      const Vec3& point, const Vec3& normal, Escape&& escape,
                      const SkyRefinement* refine = nullptr, Rng* jitter = nullptr) {
    for (const auto& path : sensor_sky_path_list(scene, specular, patches, cells, depth, point,
                                                 normal, refine, jitter))
        escape(path.direction, path.weight, path.slot);
}

// The variance of a jittered sky quadrature (sensor_sky_paths with `jitter`) from what its
// paths were worth, fed in the order they came: each jittered part's two passes are two
// independent estimates of it, so (v_pass0 - v_pass1)^2 summed over parts is an unbiased
// estimate of the variance of their mean, the value taken (v: each path's half-weighted
// contribution). The centres (slot -1) are a fixed quadrature: not in it.
class SkyQuadratureVariance {
  public:
    void add(std::int64_t slot, double value) {
        if (slot < 0) return;
        if (slot / 2 != cell_) flush(), cell_ = slot / 2;
        difference_ += slot % 2 == 0 ? value : -value;
    }
    double variance() {
        flush();
        return sum_;
    }

  private:
    void flush() {
        sum_ += difference_ * difference_;
        difference_ = 0;
    }
    std::int64_t cell_ = -1;
    double difference_ = 0, sum_ = 0;
};

// The direct sun at a sensor (lux): the beam's normal illuminance x cos x what glass lets
// through on the straight path to the sun (a path that leaves the scene within the sun's
// disc, 0.533 degrees across); 0 when the sun is down or blocked.
// With `mirrors`, the sun's image in each planar mirror it shines on counts too (a virtual
// source: the beam seen in the mirror, by its reflectance at the angle, where the mirror is
// in view and the reflected beam leaves the scene).
double sensor_sun(const RayScene& scene, const SpecularSurfaces& specular, int depth,
                  const Vec3& point, const Vec3& normal, const Vec3& sun_direction,
                  double normal_illuminance, const PlanarMirrors* mirrors = nullptr);

// The sky's part of a daylight solution (rad-solve --direct FILE.sky): each patch's radiosity
// per sky patch at unit radiance, RGB.
struct DaylightSolution {
    SkyPatches patches;
    SkyFrame frame;
    std::vector<float> radiosity; // [(j * patches.count() + s) * 3 + c]
};
// From a solution's header (sky_subdivision, north) and its light groups ground, sky1...;
// InputError naming `path` when it was not solved with a .sky.
DaylightSolution daylight_solution(const radfmt::RadiosityData& solution,
                                   const radfmt::Header& header, const std::string& path);
// Whether a solution was solved with a .sky (its header says sky_subdivision).
bool is_daylight_solution(const radfmt::Header& header);
// The compass a daylight solution was made for (its header's north).
SkyFrame daylight_frame(const radfmt::Header& header, const std::string& path);

// The sky patch the sun is in, and the luminance that patch would need to give the sun's
// beam illuminance; none when the sun is down or has no beam.
struct SunPatch {
    std::size_t patch = 0;
    double luminance = 0;
};
std::optional<SunPatch> sun_patch(const SkyPatches& patches, const Sky& sky);

// A sky's patch luminances for light the room reflects: each patch's mean (side x side
// directions), the sun's beam added to the patch it is in as the luminance that patch would
// need to give the beam's illuminance.
std::vector<double> patch_luminance_with_sun(const SkyPatches& patches, const Sky& sky,
                                             int side = 16);
// Each patch's radiosity for a weight per sky patch: the sum over sky patches s of
// weights[s] x s's group (at unit radiance: the weight is a radiance, W/m^2/sr).
std::vector<Rgb> mix_sky_groups(const DaylightSolution& solution,
                                const std::vector<double>& weights);
// Each patch's radiosity under `sky`: every sky patch's group at the radiance its luminance
// is (L / 179 W/m^2/sr per channel, patch_luminance_with_sun). What rad-shade --sky shows.
std::vector<Rgb> sky_radiosity(const DaylightSolution& solution, const Sky& sky);

struct DaylightOptions {
    int sky_side = 8; // directions per sky patch at a sensor: side x side
    int rays = 1024;  // the room's reflected light: cosine-weighted rays per sensor
    // Under one sky, more batches of the reflected light's rays until its standard error is
    // at most `accuracy` of the sensor's lux, or `max_rays` are cast (0: exactly `rays`).
    // The coefficients (a year's) take `rays`.
    double accuracy = 0;
    int max_rays = 4096;
    std::uint64_t seed = 1;
    int specular_depth = kDefaultSpecularDepth;
    // What each channel of the chain's RGB is worth at a sensor per unit of white light:
    // luminous (Radiance's weights, which add up to 1: lux), or another response's band
    // weights (melanopic: melanopic EDI); `beam_weight` is what light through grey glass is
    // worth (their sum), for the sun's beam, which is followed as luminous.
    Rgb channel_weights{0.265, 0.670, 0.065};
    double beam_weight = 1;
};

// The options for melanopic EDI (lx) instead of lux, for a sky of `spectrum`'s light: each
// band of the chain's RGB weighed by its melanopic share (CIE S 026), so that what the room's
// colours do to each band, they do to the melanopic light.
DaylightOptions melanopic_daylight_options(DaylightOptions options, const Spectrum& spectrum);

// Daylight at sensors of one solved mesh.
class DaylightSensors {
  public:
    DaylightSensors(const radfmt::MeshData& mesh, DaylightSolution solution,
                    DaylightOptions options);
    ~DaylightSensors();
    // Lux per cd/m^2 of each sky patch (the ground first) at a sensor: seen directly, and
    // by the light the room reflects (rays taking each patch's radiosity per sky patch).
    struct Coefficients {
        std::vector<double> direct, reflected;
    };
    Coefficients coefficients(const Vec3& point, const Vec3& normal, std::uint64_t index) const;
    // The reflected coefficients batch by batch ([batch * sky patches + s]; their mean is
    // Coefficients::reflected), each batch's rays from its own stream; `batches` their count.
    std::vector<double> reflected_batch_coefficients(const Vec3& point, const Vec3& normal,
                                                     std::uint64_t index, int& batches) const;
    int reflected_batch_count() const; // how many batches those are (0: no reflected light)
    // Under one sky: the sky seen directly, exactly (its luminance along each path), the
    // light the room reflects (the coefficients x the patches' mean luminance, the sun's
    // beam in the patch it is in) and the sun's beam; lux.
    // `reflected_error`: the standard error of `reflected` from its rays' independent batches
    // (NaN with a single batch); the sky seen directly and the sun are computed by fixed
    // directions, not sampled, and have none.
    struct Illuminance {
        double sky = 0, reflected = 0, sun = 0;
        double reflected_error = 0;
        // The sky seen directly: the standard error of its jittered quadrature where an
        // opening's edge crosses the sky (sensor_sky_paths); the rest is by cell centres.
        double sky_error = 0;
        // The standard error of total(): the two parts' are independent.
        double error() const { return std::hypot(reflected_error, sky_error); }
        int rays = 0;           // the reflected light's rays cast
        bool at_budget = false; // stopped at max_rays before the accuracy
        double total() const { return sky + reflected + sun; }
    };
    Illuminance illuminance(const Sky& sky, const Vec3& point, const Vec3& normal,
                            std::uint64_t index) const;
    // The same at every sensor, in parallel (sensor k's stream from k); progress on stderr
    // when it is a terminal and not `quiet`.
    std::vector<Illuminance> illuminance(const Sky& sky, std::span<const Vec3> points,
                                         std::span<const Vec3> normals, bool quiet) const;
    // The sun's beam at a sensor (lux), see sensor_sun.
    double sun(const Vec3& point, const Vec3& normal, const Vec3& direction, double lux) const;
    // Per sensor, 1 where it is inside a closed object or behind a surface (of 64 rays from
    // it, most that meet a surface meet a back that lets no light through: sees_mostly_backs),
    // as rad-gather's lighting mode judges its sensors: such a sensor has no value (NaN) and
    // counts in no statistic. Deterministic.
    std::vector<std::uint8_t> inside(std::span<const Vec3> points,
                                     std::span<const Vec3> normals) const;
    const SkyPatches& patches() const { return solution_.patches; }
    const SkyFrame& frame() const { return solution_.frame; }

  private:
    // What a path's RGB weight is worth (options_.channel_weights; luminous by default).
    double weighted(const Rgb& w) const {
        const auto& c = options_.channel_weights;
        return c[0] * w[0] + c[1] * w[1] + c[2] * w[2];
    }
    std::vector<double> reflected(const Vec3& point, const Vec3& normal, std::uint64_t index) const;
    // The reflected light's coefficients batch by batch: `each(coefficients)` once a batch,
    // every batch of stratified rays from its own stream (their mean is reflected()).
    // Batches [first, end) (end -1: the plan's count).
    template <class Each>
    void reflected_batches(const Vec3& point, const Vec3& normal, std::uint64_t index, Each&& each,
                           int first = 0, int end = -1) const;
    const radfmt::MeshData& mesh_;
    DaylightSolution solution_;
    DaylightOptions options_;
    SkyPatches::Cells cells_; // each sky patch's directions at a sensor
    SkyRefinement refine_;    // finer, where an opening's edge crosses a patch
    std::unique_ptr<RayScene> scene_;
    std::unique_ptr<SpecularSurfaces> specular_;
    PlanarMirrors mirrors_; // the sun's images in them
};

// The year's metrics' standard errors. The sky seen directly and the sun are exact; the room's
// reflected light comes from B batches of rays. Replicate b of the year adds to every hour
// batch b's deviation from the batches' mean, scaled to the size of the mean's error (1 /
// sqrt(B - 1)): a draw of the error the estimate has, correlated over the hours as the
// estimate's is (the same rays see the room for every sky). A figure's standard error is its
// replicates' root mean square deviation from the figure itself; the plane's figures (sDA,
// means) take every sensor's replicate b together (the sensors' rays are independent). (A
// leave-one-batch-out jackknife moves the light by a quarter of that and flips too few hours
// of a count over a threshold: it gave 0 at most sensors and held the truth at 88%.) ASE
// counts the sun's beam alone, exact: 0.
struct AnnualReplicates {
    int batches = 0;                       // B; 0: not computed (no reflected light, 1 batch)
    std::vector<double> da300, udi_useful; // [sensor * B + b], shares
};
struct AnnualErrors {
    std::vector<double> da300, udi_useful; // per sensor of the part (NaN: not known)
    double sda = std::numeric_limits<double>::quiet_NaN();
    double da300_mean = std::numeric_limits<double>::quiet_NaN();
    double udi_useful_mean = std::numeric_limits<double>::quiet_NaN();
};
struct AnnualMetrics;
AnnualErrors annual_errors(const AnnualReplicates& replicates, const AnnualMetrics& metrics,
                           std::size_t first = 0);

// A year's skies as the daylight coefficients take them: per hour Perez's sky from the weather
// file's radiation (the sun at mid-hour), each sky patch's mean luminance (4 x 4 directions a
// patch) for the sky seen directly, and for the light the room reflects the same with the
// sun's beam added to the patch it is in (the luminance that patch would need to give the
// beam's illuminance); the sun's direction and beam. Parallel over the hours.
struct HourlySkies {
    std::size_t count = 0;                // sky patches
    std::vector<float> direct, reflected; // [hour * count + s], cd/m^2
    std::vector<Vec3> sun;                // per hour
    std::vector<double> sun_lux;          // the beam's normal illuminance, 0 when down
    std::vector<std::int64_t> sun_patch;  // the patch the beam was added to (-1: none)
    std::vector<double> beam_luminance;   // what was added to it, cd/m^2
    std::vector<std::uint8_t> adjusted;   // per hour: its Perez sky was adjusted
    // Per hour: the record gives light (DNI or DHI above 0) though the sun is below the
    // horizon all hour (a weather file's fault: Mannheim's gives DNI 47 W/m^2 through 1,316
    // nights' hours); dark all the same.
    std::vector<std::uint8_t> night_light;
};
HourlySkies hourly_skies(const Weather& weather, const SkyPatches& patches, const SkyFrame& frame,
                         double ground);
// An hour's sky as a year takes it: Perez's from the record's radiation with the sun at the
// hour's middle; none when the hour is dark (the sun far below the horizon, `night_light`
// set when the record gives light all the same, or no light at all).
std::optional<Sky> hour_sky(const Weather& weather, const WeatherHour& hour, const SkyFrame& frame,
                            double ground, bool* night_light);
// `--sky epw:FILE --date D --time T`: the sky of the record of the hour ending at or after T
// on D (hour_sky; dark when it is). InputError without a date and time, or with no record.
Sky weather_file_sky(const std::string& path, const std::string& date, const std::string& time,
                     const SkyFrame& frame, double ground);

// A year at sensors from a weather file: per hour Perez's sky from its radiation (the sun at
// mid-hour), the sky's light through the coefficients, the sun's beam traced at each sensor.
// `occupied`: one flag per hour. `ground`: the ground's reflectance. Parallel over the
// sensors; deterministic. `replicates` (may be null) receives each sensor's replicates of the
// year (1.4 times the work at 1000 sensors). `notes` (may be null)
// receives one line for the hours whose Perez sky was adjusted at the model's edges
// (Sky::adjusted), with their count and the first.
radfmt::AnnualData annual_illuminance(const DaylightSensors& sensors,
                                      const std::vector<Vec3>& positions,
                                      const std::vector<Vec3>& normals, const Weather& weather,
                                      const std::vector<std::uint8_t>& occupied, double ground,
                                      bool quiet = true, std::vector<std::string>* notes = nullptr,
                                      AnnualReplicates* replicates = nullptr);
// The same under skies already made (hourly_skies of the weather, the sensors' sky patches
// and compass, the ground): years of several solutions, or a year and its glare, share them.
radfmt::AnnualData annual_illuminance(const DaylightSensors& sensors, const HourlySkies& skies,
                                      const std::vector<Vec3>& positions,
                                      const std::vector<Vec3>& normals, const Weather& weather,
                                      const std::vector<std::uint8_t>& occupied, bool quiet = true,
                                      std::vector<std::string>* notes = nullptr,
                                      AnnualReplicates* replicates = nullptr);

// A year lit by several solutions (a window's states, shading.hpp): adds to `replicates` (its
// batches 0 at the first call: sized and zeroed here) the replicates of the occupied hours
// `counted` marks, which this state's `sensors` lit under `skies` (hourly_skies), against the
// year's `lux` as operated; shares are of `occupied_hours`, all the year's. Called once per
// state, the replicates are those annual_illuminance gives a year of one state.
void add_annual_replicates(const DaylightSensors& sensors, const HourlySkies& skies,
                           const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                           const std::vector<std::uint8_t>& counted, int occupied_hours,
                           const std::vector<float>& lux, AnnualReplicates& replicates);

// The occupied hours: 08:00 to 18:00 local standard time every day (LM-83's default), or
// read from `path`: one 0 or 1 a line for each hour of the year (# comments and blank lines
// skipped; InputError "FILE:LINE" otherwise, or for a count other than `hours`).
std::vector<std::uint8_t> default_occupancy(const Weather& weather);
std::vector<std::uint8_t> read_occupancy(const std::string& path, std::size_t hours);
// One 0 or 1 a line for each of `hours` hours (# comments and blank lines skipped), `what`
// naming the file's kind in its errors ("occupancy": "an occupancy line is 0 or 1 ...").
std::vector<std::uint8_t> read_hourly_flags(const std::string& path, std::size_t hours,
                                            std::string_view what);

// Climate-based metrics over the occupied hours (IES LM-83-12, and UDI after Nabil and
// Mardaljevic): per sensor DA300 (share of hours at 300 lx or more), the hours the sun's
// beam alone gives 1000 lx or more, and UDI's three bins (under 100, 100 to 3000, over 3000
// lx); over the plane sDA300/50% (share of sensors with DA300 >= 50%) and ASE1000,250h
// (share of sensors with more than 250 such hours).
struct SensorMetrics {
    double da300 = 0, udi_low = 0, udi_useful = 0, udi_high = 0;
    int sun_hours = 0;
    bool valid = true; // false: inside an object (NaN shares); left out of the plane's figures
};
struct AnnualMetrics {
    std::vector<SensorMetrics> sensors;
    int occupied_hours = 0;
    std::size_t counted = 0;                            // sensors with a value
    double sda = 0, ase = 0, udi_useful = 0, da300 = 0; // shares in [0, 1]; means over sensors
};
// `inside` (empty, or one flag per sensor, DaylightSensors::inside): those sensors get no
// value and count in no figure of the plane.
AnnualMetrics annual_metrics(const radfmt::AnnualData& year,
                             std::span<const std::uint8_t> inside = {});
// The plane's figures (sDA, ASE, means) of some sensors' metrics: a part of a plane (a
// calculation surface) is summarised as annual_metrics summarises the whole. Sensors not
// valid are left out; `counted` is how many are in.
AnnualMetrics summarise_sensor_metrics(std::vector<SensorMetrics> sensors, int occupied_hours);

// Daylight factors' summary: mean, median, min, max (%) and the share of sensors at 2% or more,
// over the sensors with a value (NaN: inside an object, counted apart).
struct DaylightFactorSummary {
    double mean = 0, median = 0, min = 0, max = 0, above2 = 0;
    std::size_t counted = 0, without = 0;
};
DaylightFactorSummary summarise_daylight_factors(std::vector<double> factors);

// The sun's beam made sharp in a solution under one sky (#69 item 5), as rad-gather traces it
// at sensors: the solve spread the beam's direct light over every patch that sees the sky
// patch the sun is in (its light group at the beam's radiance), so the patch on the floor is as
// blurred as that sky patch is wide. What that spread put on each patch, rho x D x the beam's
// radiance (D: the .sky's irradiance from the patch at unit radiance), is taken out of the
// radiosity, and each surface point seen gets the beam's own light (beam_radiosity); what the
// beam's light reflects further stays as the solve spread it.
struct SharpBeam {
    std::vector<Rgb> radiosity;    // under the sky, the spread beam taken out
    Vec3 direction{0, 1, 0};       // towards the sun
    double normal_illuminance = 0; // lux; 0: no beam (nothing was taken out)
};
// `under_sky`: sky_radiosity(solution, sky), the beam spread in it.
SharpBeam sharp_beam(const DaylightSolution& solution, const radfmt::SkyData& view,
                     const radfmt::MeshData& mesh, const Sky& sky,
                     const std::vector<Rgb>& under_sky);
// The spread direct light of sky patch `sky_patch` at `radiance` (W/m^2/sr) on every patch:
// rho x D (the page's sun layers take it out of their group).
std::vector<Rgb> spread_beam(const radfmt::SkyData& view, const radfmt::MeshData& mesh,
                             std::size_t sky_patch, double radiance);
// The exitance (W/m^2) the beam gives a surface point facing `normal` of reflectance `rho`:
// rho x its irradiance there (sensor_sun: through glass, unless shadowed) / 179.
Rgb beam_radiosity(const SharpBeam& beam, const RayScene& scene, const SpecularSurfaces& specular,
                   int depth, const Rgb& rho, const Vec3& point, const Vec3& normal);

// A small basis for relighting a daylight solution by sky (the viewer page): K components,
// each a radiosity per patch, whose weights are linear in the sky patches' luminance; chosen
// (principal components of the solutions under `skies`, area-weighted) to reproduce those
// skies best. A sky L (cd/m^2 per sky patch, patch_luminance_with_sun) gives component k the
// weight sum_s weights[k][s] L[s]; the radiosity is then sum_k weight_k values[k].
struct DaylightBasis {
    std::vector<std::vector<Rgb>> values;     // K x patches
    std::vector<std::vector<double>> weights; // K x sky patches
    // Relative area-weighted rms error of the radiosity over `skies`: the mean and the worst.
    double mean_error = 0, worst_error = 0;
};
// `areas`: the patches'. The fewest components (up to `max_components`) whose mean error
// over `skies` (luminance vectors, at least one) is at most `target_error`.
DaylightBasis daylight_basis(const DaylightSolution& solution, const std::vector<double>& areas,
                             const std::vector<std::vector<double>>& skies, int max_components,
                             double target_error);
// A day's skies (Sky::of_day) over a year at `where` (every fifth day, each daylight hour at
// half past): the patch luminances of the sky and the ground without the sun's beam, and
// the sky patches the sun is in (ascending, each once). What the viewer page shows.
struct YearOfSkies {
    std::vector<std::vector<double>> skies;
    std::vector<std::size_t> sun_patches;
};
YearOfSkies day_year(const SkyPatches& patches, const SkyFrame& frame, const Location& where,
                     double ground, Sky::Day day);
inline YearOfSkies clear_year(const SkyPatches& patches, const SkyFrame& frame,
                              const Location& where, double ground) {
    return day_year(patches, frame, where, ground, Sky::Day::clear);
}

} // namespace rad
