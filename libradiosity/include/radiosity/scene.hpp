// Reading OBJ+MTL scenes and subdividing them into a conforming patch mesh (rad-mesh).
#pragma once
#include "radfmt/kinds.hpp"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rad {

// One input face as written in the OBJ, before subdivision.
struct Polygon {
    std::vector<std::uint32_t> vertices; // indices into Scene::vertices
    std::uint32_t group = 0;
    std::uint32_t material = 0;
    int line = 0; // line of the 'f' statement, for messages
    // Sum of the face's `vn` normals when every corner has one (zero otherwise): what the
    // file says the face's front is, to check the winding against.
    radfmt::Vec3 vn_sum{0, 0, 0};
};

struct Scene {
    std::string path;
    std::vector<radfmt::Vec3> vertices;
    std::vector<Polygon> polygons;
    std::vector<std::string> groups;
    std::vector<radfmt::Material> materials;
    std::vector<std::string> material_files; // the MTL files read, for provenance hashes
};

// Loads an OBJ with its MTL via tinyobjloader, after a line-by-line check that names the
// file and line of every malformed vertex, face, index or material reference.
Scene load_obj(const std::filesystem::path& path);

struct DuplicateFaces {
    std::size_t removed = 0;
    int first_line = 0;          // the first face dropped
    int first_original_line = 0; // the face it repeats
};
// Drops faces whose corners repeat an earlier face's (welded by position, same winding,
// from any starting corner); a face and its reverse are both kept (two sides of a sheet).
DuplicateFaces remove_duplicate_faces(Scene& scene);

struct SubdivisionOptions {
    double max_edge = 0; // 0: no limit
    double max_area = 0; // 0: no limit
    std::map<std::string, double> max_edge_by_group;
    std::map<std::string, double> max_area_by_group;
    double planarity_tolerance = 1e-3; // relative to the face's size
};

struct SubdivisionReport {
    std::size_t degenerate_dropped = 0;
    std::size_t polygons_triangulated = 0;
};

// Splits quads into regular grids of quads and triangles into triangles, with the number
// of segments of every edge agreed between the faces sharing it, so the result has no
// T-vertices. Polygons with more than 4 vertices (or concave quads) are triangulated first.
radfmt::MeshData subdivide(const Scene& scene, const SubdivisionOptions& options,
                           SubdivisionReport* report = nullptr);

struct Topology {
    std::size_t edges = 0;
    std::size_t boundary_edges = 0;   // edges with one patch: light can leak there
    std::size_t rejected_patches = 0; // patches OpenMesh could not attach (non-manifold)
};
// Builds the patch mesh in OpenMesh to report its adjacency: open edges, non-manifold parts.
Topology analyze_topology(const radfmt::MeshData& mesh);

} // namespace rad
