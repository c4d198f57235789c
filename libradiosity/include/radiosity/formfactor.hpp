// Form factors F_ij (equation 5 of the paper) for every pair of patches. The methods are
// plugins (formfactor_method.hpp); this is what callers use.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rad {

// rad-ff's default method, "auto": analytic (exact contour integrals, O(n^2) pairs) up to this
// many patches, where it takes a few tens of seconds on 2 cores; hemisphere (rays, O(n)) above.
inline constexpr std::size_t kAutoAnalyticPatches = 2500;
// The method "auto" stands for with this many patches.
std::string automatic_form_factor_method(std::size_t patches);

// The hemi-cube's pixels across its top face by default: 3 R^2 rays a patch (7500), about
// what hemisphere casts by default.
inline constexpr int kDefaultHemicubeResolution = 50, kMaxHemicubeResolution = 4096;
// Rays (pixels) of a hemi-cube: the top face R x R and four half faces R x R/2.
inline constexpr std::uint64_t hemicube_rays(int resolution) {
    return 3 * std::uint64_t(resolution) * std::uint64_t(resolution);
}

struct FormFactorOptions {
    std::string method = "analytic"; // a name from form_factor_methods()
    int samples = 0;                 // points per patch, rounded to a square (0: the method's)
    int visibility_rays = 1;         // analytic: rays per sample point towards the other patch
    int rays = 8192;                 // hemisphere: rays per patch
    // hemisphere: the rays cast in this many independent batches (each its own rotation of
    // rays / batches stratified points), and each row's standard error estimated from them
    // (0: one stratified set of `rays`, no error).
    int error_batches = 0;
    int resolution = 0; // hemicube: pixels across its top face, even (0: the method's)
    std::string hemicube_origin = "spread"; // hemicube: rays from over the patch, or "centre"
    std::uint64_t seed = 1;
    bool quiet = false;
    int specular_depth = 12; // specular events a path may go through (kDefaultSpecularDepth)
};

// Rows [begin, end) of the matrix: the seam for sharded and distributed computation.
struct RowRange {
    std::uint64_t begin = 0;
    std::uint64_t end = std::numeric_limits<std::uint64_t>::max(); // clamped to the patch count
};

// Shards (rad-ff --rows, --merge). "A:B" (rows A to B, B excluded) or "K/N" (shard K of N,
// from 0: rows [K p / N, (K + 1) p / N) of p patches); throws InputError otherwise.
// "K/N" alone (shard K of N), for a split that is not into rows (hierarchical links).
struct Shard {
    std::uint64_t shard = 0, shards = 1;
};
Shard parse_shard(const std::string& text, std::uint64_t patches,
                  const std::string& what = "the mesh's patches");
RowRange parse_rows(const std::string& text, std::uint64_t patches,
                    const std::string& what = "the mesh's patches");
// The command line without --rows and with -o's value replaced by a placeholder, recorded in
// every part, so the merge can write the command one run would have.
std::string unsharded_command(int argc, const char* const* argv);
// Parts of a sharded result must cover rows [0, n) exactly once: InputError naming the rows
// in no part (and the --rows that computes them) or in two, otherwise.
struct RowPart {
    std::string path;
    std::uint64_t begin = 0, end = 0;
};
// `what` names the rows in messages ("rows", "sensors").
void require_row_cover(std::vector<RowPart> parts, std::uint64_t n,
                       const std::string& what = "rows");
// An unsharded_command with `output` (quoted as a shell would need) in the placeholder's
// place; InputError naming `part_path` when it has none.
std::string command_with_output(std::string command, const std::string& output,
                                const std::string& part_path);
// The command one run writing `output` would have had, from a part's unsharded_command.
std::string merged_command(const radfmt::Header& part, const std::string& part_path,
                           const std::string& output);
// A part's whole-number header field (rows_begin, rows_end, shard, shards): digits only,
// else FormatError naming the file.
std::uint64_t part_row(const radfmt::Header& header, const std::string& key,
                       const std::string& path);
// The headers of part files of one per-patch kind (rad-ff --luminaires or --sky with
// --rows), read and checked alike: each a part, of the same tool, inputs, fields (but a
// part's own) and unsharded command; InputError naming the odd one (`what`: "luminaires
// files"). Fills `headers`; returns each part's rows.
std::vector<RowPart> patch_row_parts(const std::vector<std::string>& paths, radfmt::Kind kind,
                                     const std::string& what, std::vector<radfmt::Header>& headers);
// The merged file's header from its first part's: the part's own fields dropped, the command
// one run writing `output` would have had.
radfmt::Header merged_part_header(const radfmt::Header& first, const std::string& first_path,
                                  const std::string& output);
struct FormFactorPart {
    std::string path;
    radfmt::Header header;
    std::uint64_t begin = 0, end = 0;
};
struct MergedFormFactors {
    radfmt::Header header; // as one run writing `output` would have made it
    std::uint64_t rows = 0, nonzeros = 0;
};
// Checks from their headers that the parts come from one mesh, method, options, seed and
// tool, and cover every row exactly once (InputError naming the gap, the overlap or the
// difference), then writes `output` from their bodies, one part read at a time (the merged
// rows beyond `memory_budget` bytes wait on disk): byte for byte what one run would have
// written there.
MergedFormFactors
merge_form_factor_parts(const std::vector<std::string>& paths, const std::string& output,
                        std::uint64_t memory_budget = std::numeric_limits<std::uint64_t>::max());

struct FormFactorStats {
    std::uint64_t rays_cast = 0;
    double seconds = 0;       // all of compute_form_factors
    double trace_seconds = 0; // the parallel row phase alone (rays and integrals)
    double mean_row_sum = 0;
    double max_row_sum = 0;
    // Per patch: cosine-weighted rays (the method's own or the probes) that reached its
    // front and its back, for back_face_warnings.
    std::vector<std::uint64_t> reached_front, reached_back;
    // Rays (cosine-weighted: the method's own or the probes) that met a back face within
    // their patch's own size, from patches where that is at least 3 rays and a tenth of
    // theirs: they started under or inside other geometry. None when contacts are imprinted
    // (rad-mesh's default) and nothing hangs a hair in front of a surface.
    std::uint64_t rays_started_inside = 0;
    std::size_t patches_started_inside = 0;
};

// Rays per patch cast to check for back faces when the method casts no cosine-weighted
// rays of its own (analytic, pairwise).
inline constexpr int kBackFaceProbeRays = 64;

// The options with the method's defaults filled in (e.g. `samples`); throws InputError for
// an unknown method.
FormFactorOptions resolve_form_factor_options(FormFactorOptions options);

// Upper bound of the memory compute_form_factors needs for `mesh`, in bytes.
std::uint64_t estimate_form_factor_memory(const radfmt::MeshData& mesh,
                                          const FormFactorOptions& options);

// How long computing rows `range` of `mesh` will take on the threads allowed, measured
// before it starts: the ray scene and the method's tables built once, then up to
// kEstimateMaxRows rows spread over the range, on one thread, for about `budget_seconds`.
inline constexpr std::size_t kEstimateMaxRows = 32;
struct FormFactorEstimate {
    double seconds = 0;       // the whole run, setup included
    double setup_seconds = 0; // the ray scene and the method's tables
    std::size_t sampled_rows = 0;
    std::size_t threads = 1;
};
FormFactorEstimate estimate_form_factor_time(const radfmt::MeshData& mesh,
                                             const FormFactorOptions& options, RowRange range = {},
                                             double budget_seconds = 0.25);

// The header fields describing how a form-factor file was computed (method, its options,
// seed): what makes two files comparable.
std::vector<std::pair<std::string, std::string>>
form_factor_header_fields(const FormFactorOptions& options);
// For a mesh with mirrors or glass, the fields that say how paths through them were
// followed (specular_depth, specular_materials); none for a mesh without.
std::vector<std::pair<std::string, std::string>>
specular_header_fields(const radfmt::MeshData& mesh, const FormFactorOptions& options);

// Row i of the matrix as the sink receives it: (column, F_ij), columns ascending.
using FormFactorEntries = std::span<const std::pair<std::uint32_t, float>>;
// What a row's rays said beside its entries: the share that arrived at back faces, and the
// row's standard error (FormFactorData::row_error; negative when not estimated).
struct FormFactorRowFacts {
    float back_fraction = 0;
    float standard_error = -1;
};
using FormFactorRowSink = std::function<void(std::size_t row, FormFactorEntries entries,
                                             const FormFactorRowFacts& facts)>;

// Computes the rows a block at a time and hands every row of the matrix to `sink`, in
// order from 0 (those outside `rows` empty), without holding the matrix: rad-ff spools them
// to disk. Rows are computed in parallel (TBB); each row draws its random numbers from
// (seed, row) alone, so the result is identical for any number of threads.
void compute_form_factor_rows(const radfmt::MeshData& mesh, const FormFactorOptions& options,
                              const FormFactorRowSink& sink, FormFactorStats* stats = nullptr,
                              RowRange rows = {});

// The same rows, held in memory (patch_count is the mesh's, rows outside `rows` empty).
radfmt::FormFactorData compute_form_factors(const radfmt::MeshData& mesh,
                                            const FormFactorOptions& options,
                                            FormFactorStats* stats = nullptr, RowRange rows = {});

// The back-face check of a computed matrix, one warning line per group found, the largest area
// concerned first:
//  - most of the group's patches send most of their rays to the back of other surfaces
//    (they face the wrong way, or what they look at does);
//  - more than 80% of the rays that reach the group arrive at its back (it faces the wrong
//    way).
std::vector<std::string> back_face_warnings(const radfmt::MeshData& mesh,
                                            std::span<const float> back_fraction,
                                            const FormFactorStats& stats);

// Exact form factor from a differential area at `point` with unit normal `normal` to a
// planar polygon (contour integral, Lambert/Sparrow); the polygon must lie in front of the
// point's tangent plane (clip it first) and face the point.
double point_to_polygon_form_factor(const Vec3& point, const Vec3& normal,
                                    std::span<const Vec3> polygon);
// One edge's term of point_to_polygon_form_factor's contour sum, for the unit directions a and b
// from the point to the edge's ends: a polygon's form factor is |the sum of its edges' terms| / 2
// pi, and an edge walked the other way gives exactly the negated term (so cells sharing an edge
// share it).
double contour_edge_term(const Vec3& a, const Vec3& b, const Vec3& normal);

// Closed forms for tests and checks (Howell's catalogue, C-11 and C-14).
double parallel_rectangles_form_factor(double a, double b, double c);      // a x b, distance c
double perpendicular_rectangles_form_factor(double h, double l, double w); // common edge l

} // namespace rad
