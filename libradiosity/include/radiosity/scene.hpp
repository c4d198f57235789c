// Reading OBJ+MTL scenes and subdividing them into a conforming patch mesh (rad-mesh).
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/materials.hpp"
#include "radiosity/surfaces.hpp"
#include "radiosity/texture.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rad {

class StageLog;

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
    // Per material, what the MTL says beyond Kd and Ke (Ka, Ks, Tf, illum), for the checks.
    std::vector<MaterialSource> material_sources;
    std::vector<std::string> material_files; // the MTL and texture files read, for provenance
    // Formats without lines (glTF and the rest assimp reads): Polygon::line numbers the faces
    // of the file from 1, and each range of them names where it comes from ("node 'Cube',
    // mesh 'Cube'"), from its first face on. Empty for OBJ, whose lines are the file's.
    struct FaceRange {
        int first = 1;
        std::string origin;
    };
    std::vector<FaceRange> face_ranges;
    // Where another object touches a face (imprint_contacts' contact lines, in 3D): planar
    // regions are not joined across them, since each side can see another room.
    std::vector<std::array<radfmt::Vec3, 2>> contact_lines;
};

// A face for messages. OBJ: "12" (its line); others: "face 12 (node 'Cube', mesh 'Cube', its
// face 3)". face_location: "scene.obj:12", or "scene.glb: face 12 (node ...)".
std::string face_number(const Scene& scene, int line);
std::string face_location(const Scene& scene, int line);

// Limits of a third-party importer (assimp: glTF, PLY, COLLADA, FBX, ...), which runs in a
// child process: a file that crashes it, hangs it or exhausts its memory is refused with
// how it failed, and the tool lives on.
struct ImportLimits {
    bool isolate = true;
    double seconds = 300;                             // wall clock; 0: no limit
    std::uint64_t memory_bytes = 0;                   // address space; 0: 80% of physical memory
    std::size_t stack_bytes = std::size_t(512) << 20; // deep nesting recurses in importers
};

struct SceneOptions {
    // Refuse what is otherwise repaired with a warning: faces without a known material, a
    // missing material library (and, in subdivide, non-planar faces).
    bool strict = false;
    radfmt::Rgb default_reflectance{{0.5, 0.5, 0.5}}; // of the material given to such faces
    // Where `mtllib` files are looked for after the OBJ's folder and the current directory.
    std::vector<std::filesystem::path> mtl_paths;
    // Formats read through assimp (glTF, PLY, COLLADA, FBX): emission in W/m^2 is their
    // emissive colour x glTF's emissiveStrength x this (their emission has no unit).
    double emission_scale = 1;
    ImportLimits import;
    // Files a scene refers to (glTF buffers and images, OBJ material libraries and textures)
    // must lie in its folder or below, unless this allows them elsewhere; special files
    // (FIFOs, devices) are never opened.
    bool allow_outside_refs = false;
    // Textures with more pixels are not decoded (a warning; the material keeps its Kd).
    std::uint64_t max_texture_pixels = kMaxTexturePixels;
    // Where reading, and the mesh stage's passes after it, show how far they are (optional).
    StageLog* stages = nullptr;
    // The most memory meshing the scene may take (rad-mesh --max-memory; 0: no limit): a scene
    // whose faces, instances counted (a glTF placing one mesh at 1000 nodes), would need more
    // (kMeshBytesPerFace each) is refused as soon as they are counted, before they are built.
    std::uint64_t max_memory = 0;
};

// What meshing takes per input face, measured (bench/import: 5e6 triangles in 1.7 GiB).
inline constexpr std::uint64_t kMeshBytesPerFace = 400;
// Refuses (InputError naming `source`) `faces` faces that would need more than `max_memory`.
void check_mesh_memory(std::uint64_t faces, std::uint64_t max_memory, const std::string& source);

// What load_obj repaired or could not find, for its warnings and summary.
struct SceneReport {
    std::size_t faces_defaulted = 0; // faces given the default material
    int first_defaulted_line = 0;
    std::string default_material;               // its name ("default", unless the scene has one)
    std::vector<std::string> unknown_materials; // usemtl names no MTL defines, "name (line N)"
    std::vector<std::string> missing_libraries; // "'name' (line N) not found; looked for .."
    // Libraries named with folders (sub/x.mtl) found by file name alone: "'name' (line N) as P"
    std::vector<std::string> libraries_found_by_name;
    std::vector<std::string> textures_averaged;     // "material: file, mean r g b"
    std::vector<std::string> textures_replacing_kd; // materials whose Kd was 0 or absent
    std::vector<std::string> texture_problems;      // missing or unreadable textures
    // How a material's file lines were taken and why ("material 'X': opaque: illum 4, but
    // ..."), where the file says more than a diffuse colour; changed: a value was scaled or
    // clamped to make it hold together.
    std::vector<std::string> materials_read, materials_changed;
    // Lights the file holds that are not surfaces (a glTF's punctual lights, a modelling
    // program's lamps): "'NAME' (point) at (x, y, z)". The chain lights with surfaces,
    // luminaires and the sky, so they light nothing.
    std::vector<std::string> lights;
    // OBJ face corners naming a vt or vn that does not exist, ignored (neither shapes a
    // patch): how many, and the first ("line 62: '5/1/1' refers to normal (vn) 1, ...").
    std::size_t dangling_corners = 0;
    std::string first_dangling;
};

// Loads an OBJ with its MTL via tinyobjloader, after a line-by-line check that names the
// file and line of every malformed vertex, face or index. MTL files are found next to the
// OBJ, in the current directory, then in `mtl_paths`; a diffuse texture (map_Kd) multiplies
// Kd by its mean linear colour (replaces Kd when Kd is 0 or absent).
Scene load_obj(const std::filesystem::path& path, const SceneOptions& options = {},
               SceneReport* report = nullptr);

// glTF 2.0 (.gltf, .glb), PLY, COLLADA (.dae), FBX and the rest assimp reads: node transforms
// applied (a mirroring one turns the winding back), group = node name, material = material
// name, reflectance = base colour (or diffuse) x its texture's mean, emission = emissive
// colour x emissiveStrength (KHR_materials_emissive_strength) x options.emission_scale.
Scene load_with_assimp(const std::filesystem::path& path, const SceneOptions& options = {},
                       SceneReport* report = nullptr);

// By extension: .obj through load_obj, anything else through load_with_assimp.
Scene load_scene(const std::filesystem::path& path, const SceneOptions& options = {},
                 SceneReport* report = nullptr);

struct DuplicateFaces {
    std::size_t removed = 0;
    int first_line = 0;                     // the first face dropped
    int first_original_line = 0;            // the face it repeats
    std::vector<std::pair<int, int>> lines; // every (dropped, repeated) pair of lines
};
// Drops faces whose corners repeat an earlier face's (welded by position, same winding,
// from any starting corner); a face and its reverse are both kept (two sides of a sheet).
DuplicateFaces remove_duplicate_faces(Scene& scene);

// rad-mesh's default limit: the longest patch edge is the scene's size (its bounding box's
// diagonal) over kSceneCells, about 20 patches across the scene's longest extent, or, where
// that is larger, the edge of a square patch of the surfaces' total area over a budget
// (SubdivisionOptions::patch_budget): a long, a tall and a cubic room of one area then get
// patches of one size (for an empty cube the two agree at the default budget of 800), where
// the diagonal alone made a tunnel's patches wider than the tunnel.
inline constexpr double kMaxEdgeFromScene = -1;
inline constexpr double kSceneCells = 20;
inline constexpr double kDefaultPatchBudget = 800;

struct SubdivisionOptions {
    double max_edge = 0; // 0: no limit; kMaxEdgeFromScene: the scene's size / kSceneCells
    double max_area = 0; // 0: no limit
    double patch_budget = kDefaultPatchBudget; // for kMaxEdgeFromScene (rad-mesh --patches)
    std::map<std::string, double> max_edge_by_group;
    std::map<std::string, double> max_area_by_group;
    double planarity_tolerance = 1e-3; // relative to the face's size
    bool strict = false;               // refuse non-planar faces instead of splitting them
    // Refuse before subdividing when the limits would make more patches than this (a typo
    // such as --max-edge 1e-4 would otherwise take all memory).
    double max_patches = 2e7;
    // Curved surfaces drawn as thin facets taken as planar faces across them, each within this
    // fraction of a cell of the facets (SurfaceOptions::max_sag; 0: the facets as drawn).
    double max_sag = kDefaultMaxSag;
};

// A group's limit (--max-edge GROUP=L, --max-area GROUP=A), or the scene's when it has none.
inline double limit_for(const std::map<std::string, double>& by_group, const std::string& group,
                        double fallback) {
    const auto it = by_group.find(group);
    return it != by_group.end() ? it->second : fallback;
}

struct SubdivisionReport {
    std::size_t degenerate_dropped = 0;
    std::size_t polygons_triangulated = 0; // more than 4 corners, or a concave quad
    // Faces whose corners leave their plane by more than the tolerance, split into
    // triangles; the worst one (distance from its plane, relative to its size) and its line.
    std::size_t nonplanar_split = 0;
    double worst_nonplanar_offset = 0, worst_nonplanar_relative = 0;
    int worst_nonplanar_line = 0;
};

// Splits quads into regular grids of quads and triangles into triangles, with the number
// of segments of every edge agreed between the faces sharing it, so the result has no
// T-vertices. Polygons with more than 4 vertices (or concave quads) are triangulated first.
radfmt::MeshData subdivide(const Scene& scene, const SubdivisionOptions& options,
                           SubdivisionReport* report = nullptr);
// `subdivide` with no limits (planarity, strictness and --max-patches as `options` say):
// the faces cleaned into planar triangles and convex quads, one patch each. Takes the
// scene's polygons and vertices (left empty) to keep the peak of memory down.
radfmt::MeshData clean_faces(Scene& scene, const SubdivisionOptions& options,
                             SubdivisionReport* report = nullptr);

// Renumbers the patches along a Morton (Z-order) curve of their centroids, quantised to
// kMortonSteps steps a side of the centroids' bounding cube, patches in one step in their
// previous order; vertices are renumbered in order of first use. Patches near each other in
// space get numbers near each other, so the columns of a form-factor row, and the radiosity
// a solver gathers through them, sit close in memory. rad-mesh's default patch order.
inline constexpr std::uint64_t kMortonSteps = std::uint64_t(1) << 21;
void order_patches_by_locality(radfmt::MeshData& mesh);
// The Morton code of `point` in cells of size `cell` from `origin` (clamped to the grid).
std::uint64_t morton_code(const Vec3& point, const Vec3& origin, double cell);

// The faces as fans of triangles, each with its face's own (Newell) normal: a mesh for a
// RayScene over the scene as written. `face_of` and `triangle_area` get one entry per
// triangle when given; faces marked in `reversed` are taken as wound the other way.
radfmt::MeshData face_triangles(const Scene& scene, std::vector<std::size_t>* face_of = nullptr,
                                std::vector<double>* triangle_area = nullptr,
                                const std::vector<bool>* reversed = nullptr);

// Contacts imprinted (rad-mesh's default): where a face of another object touches or crosses
// a face (coplanar and facing it, an edge lying in it, or going through it), the contact
// lines are cut into the face, which is replaced by the triangles of the regions they bound;
// regions enclosed by other geometry (the floor under a block, a beam's end inside a wall:
// seen from there, most surfaces show their back) are removed. Faces of one object (sharing
// a vertex position) do not imprint each other. Points closer than `tolerance` (relative to
// the scene's size) are one point, so near-coincident input makes no slivers. Vertices added
// on a face's edge are added to the other faces along that edge, so edges stay conforming.
struct ImprintReport {
    std::size_t faces_imprinted = 0, regions_removed = 0;
    double area_imprinted = 0, area_removed = 0;
    std::vector<int> removed_lines; // OBJ lines of faces that lost a region
    // Area removed by group, of regions bounded mostly by the face's own outline (not
    // footprints, bounded mostly by contact lines): what may be a mistake.
    std::map<std::uint32_t, double> removed_by_group;
};
// `turned[f]`: face f faces the other way for the hidden-region test (what --orient fix would
// flip), so that whether a region is enclosed does not depend on wrongly facing walls.
// `gap` (relative to the scene's size, like `tolerance`): an edge of another object's face
// lying within it in front of a face is a contact too, when that face reaches at least 20
// times as far out from the plane (a wall ending a hair below a ceiling, not a trim as deep as
// its distance). The contact lines are added to scene.contact_lines.
inline constexpr double kContactGap = 2e-3;
ImprintReport imprint_contacts(Scene& scene, double tolerance = 1e-7,
                               const std::vector<bool>& turned = {}, double gap = kContactGap);

struct Topology {
    std::size_t edges = 0;
    std::size_t boundary_edges = 0;   // edges with one patch: light can leak there
    std::size_t rejected_patches = 0; // patches OpenMesh could not attach (non-manifold)
};
// Builds the patch mesh in OpenMesh to report its adjacency: open edges, non-manifold parts.
Topology analyze_topology(const radfmt::MeshData& mesh);

} // namespace rad
