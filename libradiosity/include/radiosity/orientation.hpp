// Which way input faces point: cheap geometric checks on the scene before subdivision, and
// the fixes rad-mesh offers (--flip GROUP, --orient fix).
#pragma once
#include "radiosity/scene.hpp"

#include <string>
#include <vector>

namespace rad {

struct OrientationFinding {
    enum class Kind {
        AgainstNormals,    // wound against the majority of the face's own `vn` normals
        AgainstNeighbours, // winding disagrees with the rest of its connected surface
        InsideOut,         // a closed object whose surface faces inward
    };
    Kind kind;
    std::uint32_t group = 0;           // the group of the faces found
    std::vector<std::size_t> polygons; // indices into Scene::polygons, ascending
    std::vector<std::size_t> to_flip;  // what --orient fix reverses (a subset of polygons)
};

// Every finding, one per (kind, group). Connected surfaces are found by welding vertices
// by position; a closed surface facing inward is a room (fine) when it encloses the rest
// of the scene, and an object turned inside out otherwise.
std::vector<OrientationFinding> check_orientation(const Scene& scene);

// One warning line: "group pillar: 4 face(s) ... (first at scene.obj:12)".
std::string describe(const OrientationFinding& finding, const Scene& scene);

// Reverses the winding of every face of the named groups; throws InputError naming the
// known groups for an unknown one. Returns the number of faces flipped.
std::size_t flip_groups(Scene& scene, const std::vector<std::string>& groups);

// Flips the faces of the AgainstNeighbours and InsideOut findings, so every connected
// surface is consistent and closed objects face outward. Returns faces flipped per group.
std::vector<std::pair<std::string, std::size_t>>
fix_orientation(Scene& scene, const std::vector<OrientationFinding>& findings);

} // namespace rad
