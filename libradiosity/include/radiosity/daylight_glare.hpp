// Daylight glare at an eye: the daylight glare probability (DGP, Wienold and Christoffersen,
// "Evaluation methods and development of a new glare prediction model for daylight
// environments with the use of CCD cameras and RADIANCE", Energy and Buildings 38, 2006),
// computed as Radiance's evalglare computes it from a 180-degree fisheye picture, but from the
// daylight solution directly: the luminance of every direction of the view's hemisphere (the
// sky through openings and glass, the room's surfaces by their radiosity, the sun's disc),
// the vertical illuminance Ev at the eye, the glare sources (directions over a threshold,
// joined where they lie within a search radius of each other, peaks over 50000 cd/m^2 apart),
// each with its mean luminance, solid angle and position index, and
//   DGP = 5.87e-5 Ev + 0.092 log10(1 + sum(Ls^2 ws / (Ev^1.87 P^2))) + 0.159
// (evalglare's constants), times the low-light correction exp(0.024 Ev - 4) / (1 + exp(0.024
// Ev - 4)) below 1000 lx (Wienold 2009).
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/position_index.hpp"
#include "radiosity/sky.hpp"
#include "radiosity/vec.hpp"

#include <memory>
#include <vector>

namespace rad {

// A year's glare views: rings 1.5 degrees wide (9,000 directions), where one sky takes 0.5.
inline constexpr int kAnnualGlareRings = 60;

struct GlareOptions {
    // A direction belongs to a glare source when its luminance exceeds this (cd/m^2), or when
    // at most 100, this factor times the view's mean luminance (evalglare -b; its default is
    // the fixed 2000 cd/m^2).
    double threshold = 2000;
    double search_radius = 0.2; // rad: sources' directions this close are one source (-r)
    double peak = 50000;        // cd/m^2: directions over it are sources of their own (-Y)
    bool low_light = true;      // the low-light correction below 1000 lx (evalglare -C l+)
    int rings = 180;            // the hemisphere's rings from the line of sight to 90 degrees
    int specular_depth = kDefaultSpecularDepth;
};

struct GlareSource {
    double luminance = 0;   // cd/m^2, the mean over its solid angle
    double solid_angle = 0; // sr
    Vec3 direction{};       // its centre, weighted by luminance x solid angle (unit)
    double position_index = 1;
    double sigma_deg = 0, tau_deg = 0; // from the line of sight, and around it from the vertical
    bool sun = false;                  // the sun's disc
    double term() const {
        return luminance * luminance * solid_angle / (position_index * position_index);
    }
};

struct DaylightGlare {
    double ev = 0;             // lux: vertical illuminance at the eye (the view's hemisphere)
    double mean_luminance = 0; // cd/m^2 over the view's hemisphere
    double threshold = 0;      // cd/m^2, as applied
    std::vector<GlareSource> sources;
    double dgp = 0;       // with the low-light correction when asked
    double low_light = 1; // the correction's factor (1 at 1000 lx or more)
};

// DGP of vertical illuminance `ev` (lux) and `sources`; the low-light correction applied
// when `low_light` (`factor`, when not null, receives it).
double daylight_glare_probability(double ev, const std::vector<GlareSource>& sources,
                                  bool low_light, double* factor = nullptr);

// A year of DGP at a view: the hours with a value (NaN: not computed, unoccupied), the shares
// of them with DGP over 0.35, 0.40 and 0.45, the mean; and EN 17037's protection from glare
// (annex A.5): "high", "medium" or "minimum" when DGP exceeds 0.35, 0.40 or 0.45 in no more
// than 5% of those hours, else "not met".
struct GlareYear {
    int hours = 0;
    double over_035 = 0, over_040 = 0, over_045 = 0, mean = 0;
    const char* en17037() const;
};
GlareYear summarise_glare_year(const std::vector<DaylightGlare>& hours);

// The luminance a daylight solution shows an eye, under one sky at a time.
class DaylightLuminance {
  public:
    // `mesh` with the reflectances as solved; `view` the .sky the solution was solved with
    // (its direct light per patch and sky patch, to see the sun's patch sharp: the solve
    // spread the beam over the sky patch it is in, the view takes that part out of the
    // patches' radiosity and puts the beam back where it falls).
    DaylightLuminance(const radfmt::MeshData& mesh, DaylightSolution solution,
                      const radfmt::SkyData& view, int specular_depth = kDefaultSpecularDepth);
    ~DaylightLuminance();

    // Glare at `eye` looking along unit `view` (+Y up) under `sky`.
    DaylightGlare glare(const Sky& sky, const Vec3& eye, const Vec3& view,
                        const GlareOptions& options = {}) const;

    // Glare at `eye` for each hour of `skies` that `hours` marks (others: NaN), by daylight
    // coefficients: each direction's luminance per cd/m^2 of each sky patch (the sky seen
    // directly, the room's radiosity, the share of the beam the solve spread over its sky
    // patch, taken out), the hour's beam traced where each direction meets a surface and to
    // the eye. The sky seen directly takes its patches' mean luminance (as the year's
    // illuminance does), not each direction's. Parallel over the hours; deterministic.
    std::vector<DaylightGlare> annual_glare(const HourlySkies& skies,
                                            const std::vector<std::uint8_t>& hours, const Vec3& eye,
                                            const Vec3& view,
                                            const GlareOptions& options = {}) const;

  private:
    struct Lit;      // the patches' radiosity under one sky
    struct YearView; // a view's coefficients for a year
    double luminance(const Lit& lit, const Vec3& eye, const Vec3& direction) const;
    YearView year_view(const Vec3& eye, const Vec3& view, int rings) const;
    // The beam's illuminance (lux) on a plane facing the sun at `eye`, through glass.
    double sun_disc(const Vec3& sun, double normal_lux, const Vec3& eye) const;
    const radfmt::MeshData& mesh_;
    DaylightSolution solution_;
    const radfmt::SkyData& view_;
    int depth_;
    std::unique_ptr<RayScene> scene_;
    std::unique_ptr<SpecularSurfaces> specular_;
    PlanarMirrors mirrors_;
};

// The .sky a daylight solution was solved with: `path` when given, else the one its header
// records (`direct`), or that file's name beside the solution when it has moved. InputError
// naming the file when it is not there, is not of `mesh`'s geometry, or changed since.
radfmt::SkyData solution_sky_view(const radfmt::Header& solution_header,
                                  const std::string& solution_path, const std::string& path,
                                  const radfmt::MeshData& mesh, const std::string& mesh_path);

} // namespace rad
