// Which way input faces point: cheap geometric checks on the scene before subdivision, and
// the fixes rad-mesh offers (--flip GROUP, --orient fix).
#pragma once
#include "radiosity/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rad {

struct OrientationFinding {
    enum class Kind {
        AgainstNormals,    // wound against the majority of the face's own `vn` normals
        AgainstNeighbours, // winding disagrees with the rest of its connected surface
        InsideOut,         // a closed object whose surface faces inward
        RoomOutward,       // a closed room (around the rest of the scene) facing outward
        FacingAway,        // an open surface whose back sees what its front should
    };
    Kind kind = Kind::AgainstNormals;
    std::uint32_t group = 0;           // the group of the faces found
    std::vector<std::size_t> polygons; // indices into Scene::polygons, ascending
    std::vector<std::size_t> to_flip;  // what --orient fix reverses (a subset of polygons)
    // AgainstNeighbours: the rest of those faces' surfaces, which --orient fix reverses
    // instead when reversing to_flip would have the scene see more backs (a vault whose
    // larger part was drawn facing out).
    std::vector<std::size_t> instead;
    // When the group is the file's unnamed one ("default": an OBJ with no g/o lines), the
    // finding is the faces of one material, and names it and the connected surface of its
    // first face (that surface's first line).
    std::optional<std::uint32_t> material;
    int surface_line = 0;
};

// Every finding, one per (kind, group), or per (kind, material) in the unnamed group. Connected
// surfaces are found by welding vertices by position; a closed surface facing inward is a room
// (fine) when it encloses the rest of the scene, and an object turned inside out otherwise.
std::vector<OrientationFinding> check_orientation(const Scene& scene);

// Visibility voting with rays, for what topology cannot tell (a room modelled as seen from
// outside, a floor facing down): every connected surface except closed objects casts
// cosine-weighted rays from both sides, and is reported when its back sees the fronts of
// other surfaces clearly more than its front does. Run it after fix_orientation, so that
// closed objects already face outward; deterministic for a given scene.
std::vector<OrientationFinding> check_facing_by_visibility(const Scene& scene);

// One warning line: "group pillar: 4 face(s) ... (first at scene.obj:12)", or with no groups
// "material white, the surface from scene.obj:10: 4 face(s) ... (first at scene.obj:12)".
std::string describe(const OrientationFinding& finding, const Scene& scene);

// Reverses the winding of every face of each named group, or, where no group has the name,
// of the material of that name (rad-mesh --flip); throws InputError naming the known groups
// and materials for a name that is neither. Says per name which it was and how many faces.
struct FlipResult {
    std::string name;
    std::string what; // "group" or "material"
    std::size_t faces = 0;
};
std::vector<FlipResult> flip_groups(Scene& scene, const std::vector<std::string>& names);

// Flips the faces of the AgainstNeighbours and InsideOut findings, so every connected
// surface is consistent and closed objects face outward. Returns faces flipped per group.
std::vector<std::pair<std::string, std::size_t>>
fix_orientation(Scene& scene, const std::vector<OrientationFinding>& findings);

// Emitters facing into their fixture: per piece of an emitting material (its faces that touch,
// welded by position), when more than kLampBackShare of the light its faces send (64
// cosine-weighted rays a triangle, area-weighted, of those that meet a surface) meets the
// back of surfaces, and from their other side less than half as much would, its faces are
// turned. `keep` names the groups and materials the user turned by hand (rad-mesh --flip):
// those are left as they are. Returns every piece, turned or not. Deterministic.
inline constexpr double kLampBackShare = 0.5;
struct LampTurn {
    std::string material;
    std::size_t faces = 0;
    double backs_before = 0, backs_after = 0; // shares of its light meeting backs, each side
    int line = 0;                             // the piece's first face's
    bool kept = false; // turned by hand (its group or material named by --flip): left
    bool turned = false;
};
std::vector<LampTurn> turn_lamps_facing_backs(Scene& scene, const std::vector<std::string>& keep);

// Of the rays cast from the fronts of the scene's faces (16 cosine-weighted ones a triangle,
// area-weighted) that meet a surface, the share that meet a back: what a fix of orientation
// must lower. Deterministic (a stream per triangle).
double seen_backs(const Scene& scene);

} // namespace rad
