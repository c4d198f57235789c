// Daylight glare at an eye (daylight_glare.hpp): the luminance of the view's hemisphere from the
// daylight solution, the glare sources as evalglare finds them in a fisheye picture, and DGP.
#include "radiosity/daylight_glare.hpp"

#include "core/union_find.hpp"

#include "radfmt/chain.hpp"
#include "radiosity/error.hpp"
#include "radiosity/gather.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <numeric>
#include <unordered_map>

namespace rad {
namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = 180 / kPi;
// The sun's disc: 0.533 degrees across.
constexpr double kSunHalfAngle = 0.5 * 0.533 / kDeg;
// Evalglare's constants (evalglare.c: c1, c2, c3, a3).
constexpr double kDgpEv = 5.87e-5, kDgpLog = 0.092, kDgpConstant = 0.159, kDgpEvPower = 1.87;
// Below this Ev (lux) the low-light correction applies (Wienold 2009).
constexpr double kLowLightLux = 1000;

// One direction of the view's hemisphere.
struct Cell {
    Vec3 direction;
    double solid_angle = 0, cos_view = 0, luminance = 0;
};

// Rings of equal angular width from the line of sight to 90 degrees, each split into cells
// of equal solid angle about as wide as the ring.
std::vector<Cell> hemisphere_cells(const Vec3& view, const Vec3& up, int rings) {
    const Vec3 right = normalized(cross(view, up)), top = cross(right, view);
    const double width = 0.5 * kPi / rings;
    std::vector<Cell> out;
    for (int i = 0; i < rings; ++i) {
        const double lo = i * width, hi = lo + width, theta = lo + 0.5 * width;
        const int count = std::max(1, int(std::lround(2 * kPi * std::sin(theta) / width)));
        const double omega = 2 * kPi * (std::cos(lo) - std::cos(hi)) / count;
        for (int k = 0; k < count; ++k) {
            const double phi = 2 * kPi * (k + 0.5) / count;
            const Vec3 d = view * std::cos(theta) +
                           (right * std::cos(phi) + top * std::sin(phi)) * std::sin(theta);
            out.push_back({normalized(d), omega, std::cos(theta), 0});
        }
    }
    return out;
}

// The cells `members` (indices into `cells`) joined where they lie within `radius` of each
// other, as evalglare joins glare pixels: each group's members (indices into `cells`), the
// groups in the order of their first member.
std::vector<std::vector<std::size_t>>
join_near(const std::vector<Cell>& cells, const std::vector<std::size_t>& members, double radius) {
    UnionFind sets(members.size());
    const double chord = 2 * std::sin(0.5 * radius);
    const auto key = [&](const Vec3& d, int dx, int dy, int dz) {
        const auto q = [&](double v, int o) { return std::int64_t(std::floor(v / chord)) + o; };
        return (q(d[0], dx) * 73856093) ^ (q(d[1], dy) * 19349663) ^ (q(d[2], dz) * 83492791);
    };
    std::unordered_map<std::int64_t, std::vector<std::size_t>> buckets;
    for (std::size_t m = 0; m < members.size(); ++m)
        buckets[key(cells[members[m]].direction, 0, 0, 0)].push_back(m);
    for (std::size_t m = 0; m < members.size(); ++m) {
        const Vec3& d = cells[members[m]].direction;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = buckets.find(key(d, dx, dy, dz));
                    if (it == buckets.end()) continue;
                    for (const std::size_t o : it->second)
                        if (o > m && sets.find(o) != sets.find(m) &&
                            length(cells[members[o]].direction - d) <= chord)
                            sets.unite(o, m);
                }
    }
    auto groups = sets.groups();
    for (auto& group : groups)
        for (auto& m : group) m = members[m];
    return groups;
}

// One source of a group of cells: its mean luminance over its solid angle, its centre
// weighted by luminance x solid angle, the position index there.
GlareSource source_of(const std::vector<Cell>& cells, const std::vector<std::size_t>& group,
                      const Vec3& view, const Vec3& up) {
    GlareSource s;
    Vec3 centre{0, 0, 0};
    double flux = 0;
    for (const auto c : group) {
        s.solid_angle += cells[c].solid_angle;
        flux += cells[c].luminance * cells[c].solid_angle;
        centre = centre + cells[c].direction * (cells[c].luminance * cells[c].solid_angle);
    }
    s.luminance = flux / s.solid_angle;
    s.direction = normalized(centre);
    s.position_index = dgp_position_index(view, up, s.direction, &s.sigma_deg, &s.tau_deg);
    return s;
}

// The sources of the cells over `threshold`: those over `peak` apart from the others.
std::vector<GlareSource> cell_sources(const std::vector<Cell>& cells, double threshold,
                                      const GlareOptions& options, const Vec3& view,
                                      const Vec3& up) {
    std::vector<GlareSource> out;
    for (const bool peaks : {false, true}) {
        std::vector<std::size_t> members;
        for (std::size_t c = 0; c < cells.size(); ++c)
            if (cells[c].luminance > threshold && (cells[c].luminance > options.peak) == peaks)
                members.push_back(c);
        for (const auto& group : join_near(cells, members, options.search_radius))
            out.push_back(source_of(cells, group, view, up));
    }
    return out;
}

// The eye's vertical, +Y; a view along it has no horizon to turn about.
Vec3 eye_vertical(const Vec3& view) {
    const Vec3 up{0, 1, 0};
    if (std::abs(dot(view, up)) > 1 - 1e-6)
        throw InputError("a glare view must not look straight up or down (the eye's vertical "
                         "is +Y): tilt it");
    return up;
}

// The glare of a view's cells (their luminance set) and the sun's disc (`sun`: the beam's
// illuminance at the eye on a plane facing it, through glass; 0: none).
DaylightGlare glare_of_cells(const std::vector<Cell>& cells, double sun, const Vec3& sun_direction,
                             const Vec3& view, const Vec3& up, const GlareOptions& options) {
    DaylightGlare out;
    double flux = 0; // sum of L x omega
    for (const auto& c : cells) {
        out.ev += c.luminance * c.cos_view * c.solid_angle;
        flux += c.luminance * c.solid_angle;
    }
    const double sun_cos = sun > 0 ? dot(sun_direction, view) : 0;
    if (sun_cos > 0) {
        out.ev += sun * sun_cos;
        flux += sun;
    }
    out.mean_luminance = flux / (2 * kPi);
    out.threshold =
        options.threshold > 100 ? options.threshold : options.threshold * out.mean_luminance;
    out.sources = cell_sources(cells, out.threshold, options, view, up);
    const double sun_omega = 2 * kPi * (1 - std::cos(kSunHalfAngle));
    if (sun_cos > 0 && sun / sun_omega > out.threshold) {
        GlareSource s;
        s.sun = true;
        s.luminance = sun / sun_omega;
        s.solid_angle = sun_omega;
        s.direction = sun_direction;
        s.position_index = dgp_position_index(view, up, s.direction, &s.sigma_deg, &s.tau_deg);
        out.sources.push_back(s);
    }
    out.dgp = daylight_glare_probability(out.ev, out.sources, options.low_light, &out.low_light);
    return out;
}
} // namespace

double daylight_glare_probability(double ev, const std::vector<GlareSource>& sources,
                                  bool low_light, double* factor) {
    double dgp = kDgpConstant + kDgpEv * ev;
    if (!sources.empty() && ev > 0) {
        double sum = 0;
        for (const auto& s : sources) sum += s.term();
        dgp += kDgpLog * std::log10(1 + sum / std::pow(ev, kDgpEvPower));
    }
    dgp = std::min(dgp, 1.0);
    double correction = 1;
    if (low_light && ev < kLowLightLux) {
        const double e = std::exp(0.024 * ev - 4);
        correction = e / (1 + e);
    }
    if (factor) *factor = correction;
    return dgp * correction;
}

struct DaylightLuminance::Lit {
    const Sky& sky;
    std::vector<Rgb> radiosity; // per patch, the sun's direct share taken out
    bool sun = false;
};

DaylightLuminance::DaylightLuminance(const radfmt::MeshData& mesh, DaylightSolution solution,
                                     const radfmt::SkyData& view, int specular_depth)
    : mesh_(mesh), solution_(std::move(solution)), view_(view), depth_(specular_depth),
      scene_(std::make_unique<RayScene>(mesh)), specular_(std::make_unique<SpecularSurfaces>(mesh)),
      mirrors_(planar_mirrors(mesh, *specular_)) {
    if (view.coefficients.size() != mesh.patches.size() * view.sky_patches * 3 ||
        view.sky_patches != solution_.patches.count())
        throw InputError("the sky-view file is not of this mesh and solution (" +
                         std::to_string(view.sky_patches) + " sky patches, " +
                         std::to_string(view.coefficients.size() / 3 /
                                        std::max<std::size_t>(1, view.sky_patches)) +
                         " patches): give the .sky the solution was solved with");
}

DaylightLuminance::~DaylightLuminance() = default;

double DaylightLuminance::luminance(const Lit& lit, const Vec3& eye, const Vec3& direction) const {
    double out = 0;
    const auto& sky = lit.sky;
    follow_specular(
        *scene_, *specular_, eye, direction, Rgb{{1, 1, 1}}, depth_,
        [&](const PathHit& h) {
            if (!h.hit.front) return;
            const auto j = std::size_t(h.hit.patch);
            const auto& b = lit.radiosity[j];
            out += kRadianceEfficacy / kPi *
                   luminous(Rgb{{h.weight[0] * b[0], h.weight[1] * b[1], h.weight[2] * b[2]}});
            if (!lit.sun) return;
            // The sun's beam where it falls, sharp: reflectance x beam illuminance / pi.
            const auto& patch = mesh_.patches[j];
            const auto& rho = mesh_.materials[patch.material].reflectance;
            const Rgb seen{{h.weight[0] * rho[0], h.weight[1] * rho[1], h.weight[2] * rho[2]}};
            if (luminous(seen) <= 0) return;
            const Vec3 at = h.origin + h.direction * h.hit.distance;
            out += luminous(seen) / kPi *
                   sensor_sun(*scene_, *specular_, depth_, at, patch.normal, sky.sun_direction(),
                              sky.sun_normal_illuminance(), &mirrors_);
        },
        [&](const Vec3& d, const Rgb& w) { out += luminous(w) * sky.luminance(d); });
    return out;
}

double DaylightLuminance::sun_disc(const Vec3& sun, double normal_lux, const Vec3& eye) const {
    if (!(normal_lux > 0)) return 0;
    double through = 0;
    follow_specular(
        *scene_, *specular_, eye, sun, Rgb{{1, 1, 1}}, depth_, [](const PathHit&) {},
        [&](const Vec3& d, const Rgb& w) {
            if (dot(d, sun) >= std::cos(kSunHalfAngle)) through += luminous(w);
        });
    return normal_lux * through;
}

DaylightGlare DaylightLuminance::glare(const Sky& sky, const Vec3& eye, const Vec3& view,
                                       const GlareOptions& options) const {
    const Vec3 up = eye_vertical(view);
    // The patches' radiosity under the sky, the sun's direct share (spread over its sky
    // patch in the solve) taken out: the beam is put back sharp where it falls.
    Lit lit{sky, sky_radiosity(solution_, sky), false};
    if (const auto beam = sun_patch(solution_.patches, sky)) {
        lit.sun = true;
        const double radiance = beam->luminance / kRadianceEfficacy;
        for (std::size_t j = 0; j < lit.radiosity.size(); ++j) {
            const auto d = view_.of(j, beam->patch);
            const auto& rho = mesh_.materials[mesh_.patches[j].material].reflectance;
            for (int c = 0; c < 3; ++c)
                lit.radiosity[j][c] = std::max(0.0, lit.radiosity[j][c] - rho[c] * d[c] * radiance);
        }
    }
    auto cells = hemisphere_cells(view, up, std::max(1, options.rings));
    tbb::parallel_for(std::size_t(0), cells.size(), [&](std::size_t c) {
        cells[c].luminance = luminance(lit, eye, cells[c].direction);
    });
    const double sun =
        sky.sun_up() ? sun_disc(sky.sun_direction(), sky.sun_normal_illuminance(), eye) : 0.0;
    return glare_of_cells(cells, sun, sky.sun_direction(), view, up, options);
}

const char* GlareYear::en17037() const {
    constexpr double kShare = 0.05;
    if (over_035 <= kShare) return "high";
    if (over_040 <= kShare) return "medium";
    if (over_045 <= kShare) return "minimum";
    return "not met";
}

GlareYear summarise_glare_year(const std::vector<DaylightGlare>& hours) {
    GlareYear out;
    for (const auto& g : hours) {
        if (!std::isfinite(g.dgp)) continue;
        ++out.hours;
        out.over_035 += g.dgp > 0.35;
        out.over_040 += g.dgp > 0.40;
        out.over_045 += g.dgp > 0.45;
        out.mean += g.dgp;
    }
    if (out.hours > 0)
        for (auto* v : {&out.over_035, &out.over_040, &out.over_045, &out.mean}) *v /= out.hours;
    return out;
}

radfmt::SkyData solution_sky_view(const radfmt::Header& solution_header,
                                  const std::string& solution_path, const std::string& path,
                                  const radfmt::MeshData& mesh, const std::string& mesh_path) {
    const auto sky_path = radfmt::solution_direct_path(solution_header, solution_path, path);
    if (sky_path.empty())
        throw InputError(solution_path + " records no .sky (rad-solve --direct SKY): give it "
                                         "with --direct FILE");
    if (!std::filesystem::exists(sky_path))
        throw InputError(sky_path + ": the sky-view file the solution was solved with is not "
                                    "there (give its new place with --direct FILE)");
    radfmt::Header header;
    auto view = radfmt::read_sky(sky_path, &header);
    radfmt::require_same_geometry(sky_path, header, view.patch_count, mesh_path, mesh,
                                  "run rad-ff --sky and rad-solve again");
    if (radfmt::solution_direct_changed(solution_header, header.file_hash))
        throw InputError(sky_path + " is not the sky-view file the solution was solved "
                                    "with (it changed since): run rad-solve --direct again");
    return view;
}

// A view's coefficients for a year: per cell and sky patch the luminance (cd/m^2) per cd/m^2
// of the patch, seen directly (`sky`), by the room's radiosity (`room`) and by the share of
// the beam the solve spread over its patch (`spread`, taken out); and per cell the surfaces
// its paths meet, where each hour's beam is traced.
struct DaylightLuminance::YearView {
    struct Spot {
        Vec3 point, normal;
        double weight = 0; // luminance per lux of beam on the surface: w x rho / pi
    };
    std::vector<Cell> cells;
    std::size_t count = 0; // sky patches
    std::vector<float> sky, room, spread;
    std::vector<std::vector<Spot>> spots;
};

DaylightLuminance::YearView DaylightLuminance::year_view(const Vec3& eye, const Vec3& view,
                                                         int rings) const {
    YearView out;
    out.cells = hemisphere_cells(view, eye_vertical(view), std::max(1, rings));
    const std::size_t n = out.cells.size(), count = solution_.patches.count();
    out.count = count;
    out.sky.assign(n * count, 0.0f);
    out.room.assign(n * count, 0.0f);
    out.spread.assign(n * count, 0.0f);
    out.spots.resize(n);
    const auto& b = solution_.radiosity;
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t c) {
        float* sky = &out.sky[c * count];
        float* room = &out.room[c * count];
        float* spread = &out.spread[c * count];
        follow_specular(
            *scene_, *specular_, eye, out.cells[c].direction, Rgb{{1, 1, 1}}, depth_,
            [&](const PathHit& h) {
                if (!h.hit.front) return;
                const auto j = std::size_t(h.hit.patch);
                const auto& patch = mesh_.patches[j];
                const auto& rho = mesh_.materials[patch.material].reflectance;
                const Rgb& w = h.weight;
                for (std::size_t s = 0; s < count; ++s) {
                    const float* r = &b[(j * count + s) * 3];
                    room[s] += float(
                        (0.265 * w[0] * r[0] + 0.670 * w[1] * r[1] + 0.065 * w[2] * r[2]) / kPi);
                    const auto d = view_.of(j, s);
                    spread[s] += float(luminous(Rgb{{w[0] * rho[0] * d[0], w[1] * rho[1] * d[1],
                                                     w[2] * rho[2] * d[2]}}) /
                                       kPi);
                }
                const double weight =
                    luminous(Rgb{{w[0] * rho[0], w[1] * rho[1], w[2] * rho[2]}}) / kPi;
                if (weight > 0)
                    out.spots[c].push_back(
                        {h.origin + h.direction * h.hit.distance, patch.normal, weight});
            },
            [&](const Vec3& d, const Rgb& w) {
                sky[solution_.patches.patch_of(solution_.frame, d)] += float(luminous(w));
            });
    });
    return out;
}

std::vector<DaylightGlare> DaylightLuminance::annual_glare(const HourlySkies& skies,
                                                           const std::vector<std::uint8_t>& hours,
                                                           const Vec3& eye, const Vec3& view,
                                                           const GlareOptions& options) const {
    if (skies.count != solution_.patches.count())
        throw InternalError("annual_glare: the skies are not of the solution's sky patches");
    const auto year = year_view(eye, view, options.rings);
    const Vec3 up = eye_vertical(view);
    const std::size_t count = year.count, n = year.cells.size();
    std::vector<DaylightGlare> out(hours.size());
    tbb::parallel_for(std::size_t(0), hours.size(), [&](std::size_t t) {
        if (!hours[t]) {
            out[t].dgp = out[t].ev = std::nan("");
            return;
        }
        const float* direct = &skies.direct[t * count];
        const float* reflected = &skies.reflected[t * count];
        const std::int64_t beam = skies.sun_patch[t];
        const double sun_lux = skies.sun_lux[t];
        auto cells = year.cells;
        for (std::size_t c = 0; c < n; ++c) {
            const float* sky = &year.sky[c * count];
            const float* room = &year.room[c * count];
            double l = 0;
            for (std::size_t s = 0; s < count; ++s)
                l += sky[s] * direct[s] + room[s] * reflected[s];
            if (beam >= 0) {
                l -= year.spread[c * count + std::size_t(beam)] * skies.beam_luminance[t];
                for (const auto& spot : year.spots[c])
                    l += spot.weight * sensor_sun(*scene_, *specular_, depth_, spot.point,
                                                  spot.normal, skies.sun[t], sun_lux, &mirrors_);
            }
            cells[c].luminance = std::max(0.0, l);
        }
        const double sun = sun_lux > 0 ? sun_disc(skies.sun[t], sun_lux, eye) : 0.0;
        out[t] = glare_of_cells(cells, sun, skies.sun[t], view, up, options);
    });
    return out;
}

} // namespace rad
