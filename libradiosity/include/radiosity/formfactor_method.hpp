// Form-factor methods as plugins. A method is one file under src/formfactor/ that defines a
// FormFactorMethod and one line in src/formfactor/registry.cpp. compute_form_factors owns
// the parallel loop, the per-row random streams and the sparse packing; a method only says
// how to fill one row.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/specular.hpp"

#include <array>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace rad {

// One patch as its corners: a triangle's or quad's in `corners`, a polygon's (star-shaped
// from its corner 0, see radfmt::Patch) in the context's `polygon_points` from `more`.
struct PatchPolygon {
    std::array<Vec3, 4> corners;
    int count;
    const Vec3* more = nullptr;
    std::span<const Vec3> points() const {
        return {more ? more : corners.data(), static_cast<size_t>(count)};
    }
    bool is_polygon() const { return more != nullptr; }
};

// What every method may use, built once per mesh.
struct FormFactorContext {
    const radfmt::MeshData& mesh;
    const RayScene& scene;
    std::vector<PatchPolygon> polygons; // per patch
    std::vector<Vec3> polygon_points;   // the corners of the polygon patches
    std::vector<double> diameter;       // per patch: its longest corner-to-corner distance
    double epsilon;                     // the ray scene's offset, relative to the scene size
    // Per patch, the key of its random streams: a hash of its corners, so a patch gets the
    // same samples whatever its number (the patch order is free to change).
    std::vector<std::uint64_t> stream_key;
    // Mirrors and glass: rays go on through them (methods that follow rays), up to
    // `specular_depth` specular events.
    SpecularSurfaces specular;
    int specular_depth = kDefaultSpecularDepth;

    FormFactorContext(const radfmt::MeshData& mesh, const RayScene& scene,
                      int specular_depth = kDefaultSpecularDepth);
    // Does any corner of patch j lie strictly in front of patch i's plane?
    bool in_front(std::size_t i, std::size_t j) const;
};

// Row i of F: (column, F_ij) for the non-zero entries, columns ascending.
using FormFactorRow = std::vector<std::pair<std::uint32_t, float>>;

// What one row's cosine-weighted rays met, for the back-face check: a patch whose rays
// mostly arrive at the back of other surfaces, or a surface mostly reached from behind,
// probably faces the wrong way. Kernels that cast such rays record each one; for the others
// compute_form_factors casts a few probe rays per row.
struct RayLog {
    std::uint32_t rays = 0;
    std::uint32_t back_hits = 0;
    // This thread's counters, two per patch: rays that reached its front and its back. One
    // patch's two share a cache line: a ray's hit costs one memory access, not one per array.
    std::uint32_t* counters = nullptr;
    static constexpr std::size_t kCountersPerPatch = 2;
    // Rays that met a back face closer than `near` (the patch's own size): they started
    // under or inside other geometry (a contact not imprinted, surfaces crossing).
    double near = 0;
    std::uint32_t started_inside = 0;
    // The row's standard error, when the method estimated one (FormFactorOptions::error_batches).
    float standard_error = -1;
    void record(std::int64_t hit, bool front, double distance = 1e300) {
        ++rays;
        if (hit < 0) return;
        if (front) {
            ++counters[2 * hit];
        } else {
            ++back_hits;
            ++counters[2 * hit + 1];
            if (distance < near) ++started_inside;
        }
    }
    // A ray that reached `patch`'s front, counted by the kernel itself and added with
    // add_fronts once per row (as record would have counted it ray by ray).
    void record_counted_front() { ++rays; }
    void add_fronts(std::size_t patch, std::uint32_t count) { counters[2 * patch] += count; }
};

// A method prepared for one mesh: computes rows, from many threads at once.
class RowKernel {
  public:
    virtual ~RowKernel() = default;
    // Fills `row` (given empty) with row i, drawing every random number from `rng`, the
    // row's own stream, and records its cosine-weighted rays (if it casts any) in `log`.
    // Returns the number of rays cast.
    virtual std::uint64_t compute_row(std::size_t i, Rng& rng, FormFactorRow& row,
                                      RayLog& log) const = 0;
};

class FormFactorMethod {
  public:
    virtual ~FormFactorMethod() = default;
    virtual std::string_view name() const = 0;
    // One line for --help: what the method does and when to use it.
    virtual std::string_view summary() const = 0;
    // Fills in the method's defaults (options the user left at 0).
    virtual void apply_defaults(FormFactorOptions& options) const = 0;
    // The fields recorded in the .ff header after `method` and before `seed`.
    virtual std::vector<std::pair<std::string, std::string>>
    header_fields(const FormFactorOptions& options) const = 0;
    // The most entries one row can have: bounds the memory of the result. Every patch
    // unless the method knows a tighter bound.
    virtual std::uint64_t max_row_entries(const radfmt::MeshData& mesh,
                                          const FormFactorOptions&) const {
        return mesh.patches.size();
    }
    // Memory the method's tables and per-thread scratch take, beyond the rows: whatever
    // grows with the options must be counted, or --max-memory guards nothing.
    virtual std::uint64_t working_memory(const radfmt::MeshData&, const FormFactorOptions&,
                                         unsigned /*threads*/) const {
        return 0;
    }
    // Whether its kernel records cosine-weighted rays in the RayLog (else rows are probed).
    virtual bool logs_rays() const { return false; }
    // Whether its rays go on through mirrors and glass (FormFactorContext::specular).
    virtual bool follows_specular() const { return false; }
    // Per-mesh preparation (tables, per-thread scratch); the kernel may keep `context`.
    virtual std::unique_ptr<RowKernel> prepare(const FormFactorContext& context,
                                               const FormFactorOptions& options) const = 0;
};

// Refuses (InputError) a mesh with mirrors or glass for a method that does not follow them.
void require_specular_support(std::string_view method, bool follows, const radfmt::MeshData& mesh);

// Every registered method, in the order --help lists them.
std::span<const FormFactorMethod* const> form_factor_methods();
std::vector<std::string> form_factor_method_names();
// Throws InputError naming the known methods when `name` is not one of them.
const FormFactorMethod& form_factor_method(std::string_view name);

} // namespace rad
