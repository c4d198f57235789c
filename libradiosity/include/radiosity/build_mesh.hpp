// rad-mesh's stage as a pipeline of passes (libradiosity/src/mesh/), each a function with its
// input, its output and its part of the report:
//   load (OBJ+MTL or assimp) -> duplicates -> orientation -> coincident faces -> imprinting
//   -> faces (clean triangles and quads) -> planar regions and their grids -> two-sided -> order
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/surfaces.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace rad {

struct MeshOptions {
    SceneOptions scene;               // reading: materials, strictness
    SubdivisionOptions subdivision;   // limits, planarity; for --surfaces faces the subdivision
    bool regions = true;              // grid planar regions (false: each face on its own)
    bool imprint = true;              // cut contacts, remove hidden regions
    double contact_gap = kContactGap; // a gap this much of the scene's size is a contact
    bool orient_fix = false;          // --orient fix (else only warn)
    std::vector<std::string> flip;    // groups (or materials) reversed by hand
    bool turn_lamps = true;           // emitters facing into their fixture turned (--keep-lamps)
    bool verbose = false;             // every warning line (else at most 20 of a kind)
    std::vector<std::string> two_sided;
    std::vector<std::string> thin;          // refracting materials or groups made thin panes
    std::vector<std::string> transmittance; // MATERIAL=r,g,b: glass's transmittance
    bool two_sided_emission = false;
    bool morton_order = true; // patches along a Z-order curve (else in face order)
};

// What the passes say, in order. Warnings and changes are printed whatever -q says (the mesh
// differs from the file, or something needs a look); notes only in the summary.
struct MeshReport {
    enum class Kind { Warning, Note, Fix, Change };
    struct Line {
        Kind kind;
        std::string text;
    };
    std::vector<Line> lines;
    SurfaceReport surfaces;
    bool regions = false;
    void add(Kind kind, std::string text) { lines.push_back({kind, std::move(text)}); }
};

// The passes in order; throws InputError for input it refuses.
radfmt::MeshData build_mesh(const std::filesystem::path& input, const MeshOptions& options,
                            MeshReport& report, Scene* scene_out = nullptr);

// The passes, each on its own (libradiosity/src/mesh/<name>_pass.cpp).
Scene load_pass(const std::filesystem::path& input, const SceneOptions& options,
                MeshReport& report);
void duplicates_pass(Scene& scene, MeshReport& report);
// Flips by hand, the orientation checks and (--orient fix) their fixes. Returns, per face,
// whether the hidden-region test should take it as facing the other way (the findings that are
// safe to act on, when they are only warned about).
std::vector<bool> orientation_pass(Scene& scene, const MeshOptions& options, MeshReport& report);
// Returns the index before the pass of each face kept.
std::vector<std::size_t> coincident_pass(Scene& scene, MeshReport& report);
void imprint_pass(Scene& scene, const std::vector<bool>& turned, double contact_gap,
                  MeshReport& report);
// Gridding planar regions, it releases the scene's polygons and vertices once they are clean
// faces (on a large input, the memory they hold is needed for the regions).
radfmt::MeshData patch_pass(Scene& scene, const MeshOptions& options, MeshReport& report);
void two_sided_pass(radfmt::MeshData& mesh, const MeshOptions& options, MeshReport& report);
// Group and material names made names of the chain (radfmt/names.hpp), still unique; each kind
// of change is a `changed:` line.
void names_pass(radfmt::MeshData& mesh, MeshReport& report);
// --thin, and a note for each mirror and glass saying how it is taken.
void specular_pass(radfmt::MeshData& mesh, const MeshOptions& options, MeshReport& report);

} // namespace rad
