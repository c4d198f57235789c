// Luminaires: photometric files placed, aimed and turned by a layout (CSV), and the light they
// give: illuminance at a point (exact: the tables and a visibility ray, over the luminous
// opening when near) and the mean irradiance over every patch (rad-ff --luminaires, the .lum
// file), one light group per layout group.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/photometry.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rad {

// The text a set of luminaires is made from: the layout and every file it names (photometric
// files, TILT files), by their paths relative to the layout's folder. A .lum file carries
// these, so a later tool rebuilds the luminaires with no other file.
struct LuminaireSources {
    std::string layout_name; // as given (for messages)
    std::string layout_text;
    std::vector<std::pair<std::string, std::string>> files; // relative path, text
    // The light groups the rows name (a row's group, or its name when empty): known before
    // the luminaires are built, so a run too big for its memory is refused early.
    std::size_t group_count = 0;
};

// Reads `layout` and every file it names. Each path is relative to the layout's folder and
// must stay inside it (absolute paths, `..` out of it and links leading out are refused,
// naming the row), and be a regular file.
LuminaireSources read_luminaire_sources(const std::filesystem::path& layout);

struct Luminaire {
    std::string name, group;
    std::size_t group_index = 0; // into LuminaireSet::groups
    int line = 0;                // its row in the layout
    std::size_t photometry = 0;  // index into LuminaireSet::photometries
    Vec3 position{};             // the photometric centre, scene units
    Vec3 nadir{0, -1, 0};        // gamma 0 (type C), the beam axis (A, B)
    Vec3 c0{1, 0, 0}, c90{0, 0, -1};
    double maintenance = 1;
    // CIE 97's parts when the layout gives them (LLMF, LSF, LMF, RSMF; maintenance is their
    // product).
    std::array<double, 4> maintenance_parts{1, 1, 1, 1};
    bool maintenance_parts_given = false;
    double emergency = 0;   // the flux share on battery (EN 1838); 0: not an emergency luminaire
    double tilt_factor = 1; // the TILT table's multiplier at its actual tilt
    double cct = 0;         // K; 0: white (R = G = B)
    Rgb tint{{1, 1, 1}};    // RGB per W of white, luminance 1
};

struct LuminaireSet {
    std::vector<Photometry> photometries;
    std::vector<double> photometry_flux; // lm, each file's integral, computed once
    std::vector<Luminaire> luminaires;
    std::vector<std::string> groups;   // in order of first appearance
    std::vector<std::string> warnings; // flux mismatches, each naming its file
    double metres_per_unit = 1;        // the scene's unit (rad-mesh --unit)

    // Candela towards the unit direction `d` (scene frame), with maintenance and TILT.
    double intensity(const Luminaire& l, const Vec3& d) const;
    // Lumens the luminaire emits, with maintenance and TILT.
    double flux(const Luminaire& l) const;
    // The luminous opening's size across, scene units (0: a point).
    double opening_size(const Luminaire& l) const;
    std::size_t group_of(const Luminaire& l) const;
};

// Builds the luminaires from their sources. The layout's header line names the columns
// name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group (in any order; aim, spin,
// maintenance, group may be empty: aim 0,-1,0, spin 0, maintenance 1, group = name; an
// optional `cct` column tints the light, keeping its lumens; EULUMDAT's lamp CCT otherwise; an
// optional `emergency` column marks emergency luminaires with their flux share on battery).
// Orientation: spin turns the luminaire about the downward axis, counter-clockwise seen from
// above (with aim down and spin 0, C0 is +X and C90 is -Z); then the shortest rotation takes
// (0,-1,0) to the aim (straight up: 180 degrees about +X). Throws InputError "LAYOUT:LINE:".
LuminaireSet build_luminaires(const LuminaireSources& sources, double metres_per_unit);

// The metres one unit of a scene is, from rad-mesh's `unit` header field (m when absent).
double metres_per_unit(const radfmt::Header& mesh_header);
// "m", "cm", "mm", "ft", "in" -> metres; InputError otherwise.
double unit_metres(const std::string& unit);

class SpecularSurfaces;
struct PlanarMirrors;
// What lies between luminaires and what they light besides opaque surfaces (both may be null):
// thin panes, which pass their light by their transmission at each angle (its luminous share:
// a tinted pane dims, it does not tint), and planar mirrors, in which each luminaire is seen as
// its image, a point source at the mirrored position shining the mirrored direction's
// intensity, times the mirror's reflectance where the path meets it.
struct LuminaireOptics {
    const SpecularSurfaces* specular = nullptr;
    const PlanarMirrors* mirrors = nullptr;
};

// Illuminance (lux) at `point` on a surface facing `normal` from one luminaire: a point
// source with one visibility ray where the point is farther than five times the luminous
// opening, else the opening sampled (64 points, each its share of the intensity, each with
// its ray). `scene` may be null (nothing shadows). The luminaire's own surface never shadows
// it: rays end a hair in front of its centre.
double luminaire_illuminance(const LuminaireSet& set, const Luminaire& l, const Vec3& point,
                             const Vec3& normal, const RayScene* scene,
                             const LuminaireOptics& optics = {});

// Irradiance (W/m^2, RGB) at a point from every luminaire, per group (groups x RGB).
std::vector<Rgb> luminaire_irradiance(const LuminaireSet& set, const Vec3& point,
                                      const Vec3& normal, const RayScene* scene,
                                      const LuminaireOptics& optics = {});

// Per patch and group, the mean irradiance (W/m^2, RGB through the 179 lm/W white) the
// luminaires give the patch's front: the patch's exact solid angle from the luminaire times
// the intensity and visibility averaged over Gauss points weighted by cos/r^2 (far), or the
// Gauss points' illuminance (near). Rows [begin, end) computed, in parallel; deterministic.
struct DirectLightStats {
    std::uint64_t rays = 0;
    double seconds = 0;
};
// `progress`: patches done, on stderr when it is a terminal (not when quiet).
std::vector<Rgb> patch_direct_light(const radfmt::MeshData& mesh, const LuminaireSet& set,
                                    const RayScene& scene, std::uint64_t begin, std::uint64_t end,
                                    DirectLightStats* stats = nullptr, bool quiet = true,
                                    const LuminaireOptics& optics = {});

// Joins .lum parts (rad-ff --luminaires --rows) of one mesh, layout and files into the .lum one
// run would have written to `output`, byte for byte; every row exactly once (InputError naming
// a gap, an overlap or a part of other inputs). Returns the rows merged.
std::uint64_t merge_luminaire_parts(const std::vector<std::string>& paths,
                                    const std::string& output);

// A .lum's light groups and luminaire count (`recorded_count`, its header's `luminaires`; < 0:
// not recorded) must be those its layout makes (`set`): InputError naming `path` otherwise (an
// extra group in a body given a new checksum counted its light twice).
void check_luminaires_file(const LuminaireSet& set, const std::vector<std::string>& groups,
                           long recorded_count, const std::string& path);

// The luminaires a solution was solved with (rad-solve --direct: its `direct` field), rebuilt
// from the .lum at `path` (empty: the recorded one, as recorded or, when that is not there,
// beside the solution at `solution_path`), which must be the file the solve read (its hash as
// recorded) and belong to `mesh`; none when the solve had no luminaires. InputError naming the
// file and what to run otherwise.
std::optional<LuminaireSet>
solution_luminaires(const radfmt::Header& solution_header, const std::string& solution_path,
                    const std::string& path, const radfmt::MeshData& mesh,
                    const std::string& mesh_path, const radfmt::Header& mesh_header);

// A warning per luminaire whose centre is inside a closed object or behind a wall (most of
// its light, by intensity, first meets the back of a surface), naming it and its row.
std::vector<std::string> enclosed_luminaire_warnings(const LuminaireSet& set, const RayScene& scene,
                                                     const std::string& layout_name);

// Luminaires are refused (InputError at their layout row) farther than this many times the
// scene's size outside its bounds: the ray tracer cannot follow their light, and a layout
// that puts one there has a typo or the wrong unit.
inline constexpr double kMaxLuminaireDistance = 1000;
// A warning per luminaire more than 1% of the scene's size outside its bounds (`scene`, the
// mesh's box; none for a scene with no depth, a floor alone), naming it and its row;
// InputError for one past kMaxLuminaireDistance.
std::vector<std::string> luminaire_position_warnings(const LuminaireSet& set, const Box& scene,
                                                     const std::string& layout_name);

} // namespace rad
