// The parts every form-factor method shares: the per-mesh context, the parallel loop over
// rows with a random stream per row, and the packing of rows into sparse storage.
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/formfactor_method.hpp"
#include "radiosity/progress.hpp"
#include "sampling.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

namespace rad {

FormFactorContext::FormFactorContext(const radfmt::MeshData& mesh_, const RayScene& scene_,
                                     int specular_depth_)
    : mesh(mesh_), scene(scene_), epsilon(scene_.epsilon()), specular(mesh_),
      specular_depth(specular_depth_) {
    const std::size_t n = mesh.patches.size();
    polygons.reserve(n);
    diameter.assign(n, 0);
    // The stream key hashes the corners quantised to 2^-20 of the scene's size from its
    // lowest corner: the same for the scene scaled, and for nearly every patch of the scene
    // moved far away (where coordinates lose digits and some land across a step).
    const Box box = bounds(mesh.vertices);
    double size = 0;
    for (int c = 0; c < 3; ++c) size = std::max(size, box.hi[c] - box.lo[c]);
    const double steps = size > 0 ? 0x1.0p20 / size : 1.0;
    stream_key.resize(n);
    polygon_points.reserve(mesh.polygon_corners.size());
    for (const auto v : mesh.polygon_corners) polygon_points.push_back(mesh.vertices[v]);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& p = mesh.patches[i];
        PatchPolygon g{};
        g.count = p.corner_count();
        if (p.is_polygon())
            g.more = polygon_points.data() + p.corners[0];
        else
            for (int k = 0; k < g.count; ++k) g.corners[k] = mesh.vertices[p.corners[k]];
        const auto points = g.points();
        for (int a = 0; a < g.count; ++a)
            for (int b = a + 1; b < g.count; ++b)
                diameter[i] = std::max(diameter[i], length(points[a] - points[b]));
        // 12 cells for a triangle or quad (zeros after its corners), 3 a corner for a polygon.
        std::array<std::uint64_t, 12> few{};
        std::vector<std::uint64_t> many(p.is_polygon() ? 3 * g.count : 0);
        std::uint64_t* cells = p.is_polygon() ? many.data() : few.data();
        for (int k = 0; k < g.count; ++k)
            for (int c = 0; c < 3; ++c)
                cells[3 * k + c] =
                    static_cast<std::uint64_t>(std::llround((points[k][c] - box.lo[c]) * steps));
        stream_key[i] = radfmt::hash_bytes(cells, (p.is_polygon() ? many.size() : few.size()) *
                                                      sizeof(std::uint64_t));
        polygons.push_back(g);
    }
}

bool FormFactorContext::in_front(std::size_t i, std::size_t j) const {
    const auto& pi = mesh.patches[i];
    for (const auto& corner : polygons[j].points())
        if (dot(corner - pi.centroid, pi.normal) > epsilon) return true;
    return false;
}

std::string automatic_form_factor_method(std::size_t patches) {
    return patches <= kAutoAnalyticPatches ? "analytic" : "hemisphere";
}

FormFactorOptions resolve_form_factor_options(FormFactorOptions options) {
    form_factor_method(options.method).apply_defaults(options);
    return options;
}

namespace {
// Rows are computed a block at a time and handed on in order: a block holds about this many
// entries, whatever the row length, and enough rows to keep every thread busy.
constexpr std::uint64_t kBlockEntries = std::uint64_t(1) << 22;
std::size_t block_rows(std::uint64_t max_row_entries, unsigned threads) {
    const auto rows = kBlockEntries / std::max<std::uint64_t>(1, max_row_entries);
    return static_cast<std::size_t>(std::clamp<std::uint64_t>(rows, 16 * threads, 8192));
}
} // namespace

unsigned ff::active_threads() {
    return static_cast<unsigned>(
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

std::uint64_t estimate_form_factor_memory(const radfmt::MeshData& mesh,
                                          const FormFactorOptions& options) {
    const std::uint64_t n = mesh.patches.size();
    const auto& method = form_factor_method(options.method);
    const std::uint64_t per_row = method.max_row_entries(mesh, options);
    const auto threads = ff::active_threads();
    // The rows are spooled to disk a block at a time (rad-ff): two blocks of rows (4 + 4
    // bytes an entry: one computed while the other is written) and the spool's buffers,
    // row starts and fractions (12 bytes a row); Embree and the mesh take a few hundred
    // bytes per patch.
    // The ray tallies are two counters per patch and thread.
    const std::uint64_t block = std::min<std::uint64_t>(n, block_rows(per_row, threads));
    return 3 * block * per_row * 8 + n * 412 + mesh.vertices.size() * 64 + n * 8 * threads +
           method.working_memory(mesh, options, threads);
}

std::vector<std::pair<std::string, std::string>>
form_factor_header_fields(const FormFactorOptions& options) {
    const auto& method = form_factor_method(options.method);
    std::vector<std::pair<std::string, std::string>> fields{{"method", options.method}};
    for (auto& field : method.header_fields(options)) fields.push_back(std::move(field));
    if (!method.logs_rays())
        fields.emplace_back("back_face_probe_rays", std::to_string(kBackFaceProbeRays));
    fields.emplace_back("seed", std::to_string(options.seed));
    return fields;
}

std::vector<std::pair<std::string, std::string>>
specular_header_fields(const radfmt::MeshData& mesh, const FormFactorOptions& options) {
    const auto specular = mesh.specular_materials();
    if (specular.empty()) return {};
    std::string materials;
    for (const auto m : specular)
        materials += (materials.empty() ? "" : ",") + mesh.materials[m].name + "=" +
                     radfmt::specular_kind_name(mesh.materials[m].specular.kind);
    return {{"specular_depth", std::to_string(options.specular_depth)},
            {"specular_materials", materials}};
}

void require_specular_support(std::string_view method, bool follows, const radfmt::MeshData& mesh) {
    if (follows) return;
    const auto specular = mesh.specular_materials();
    if (specular.empty()) return;
    std::string names;
    for (const auto m : specular)
        names += (names.empty() ? "'" : ", '") + mesh.materials[m].name + "'";
    throw InputError("--method " + std::string(method) +
                     " does not follow light through mirrors and glass, and this mesh has "
                     "them (material " +
                     names +
                     "): use --method hemisphere or hemicube, which do (or mesh the scene "
                     "without them)");
}

void compute_form_factor_rows(const radfmt::MeshData& mesh, const FormFactorOptions& options_in,
                              const FormFactorRowSink& sink, FormFactorStats* stats,
                              RowRange range) {
    const auto start = std::chrono::steady_clock::now();
    const auto options = resolve_form_factor_options(options_in);
    const auto& method = form_factor_method(options.method);
    const std::size_t n = mesh.patches.size();
    const std::size_t first = std::min<std::uint64_t>(range.begin, n);
    const std::size_t last =
        std::max(first, static_cast<std::size_t>(std::min<std::uint64_t>(range.end, n)));

    const RayScene scene(mesh);
    require_specular_support(method.name(), method.follows_specular(), mesh);
    const FormFactorContext context(mesh, scene, options.specular_depth);
    const auto kernel = method.prepare(context, options);

    // Per-thread tallies of the rays reaching each patch's front and back (integer sums:
    // the totals do not depend on the threads).
    tbb::enumerable_thread_specific<std::vector<std::uint32_t>> reached(
        [n] { return std::vector<std::uint32_t>(RayLog::kCountersPerPatch * n, 0); });
    std::atomic<std::uint64_t> rays_cast{0}, started_inside{0};
    std::atomic<std::size_t> patches_started_inside{0};
    double sum_rows = 0, max_row = 0, trace_seconds = 0;
    const FormFactorEntries empty_row;
    const FormFactorRowFacts empty_facts{0, options.error_batches > 0 ? 0.0f : -1.0f};
    for (std::size_t i = 0; i < first; ++i) sink(i, empty_row, empty_facts);

    Progress progress("rad-ff " + options.method, last - first, options.quiet);
    const auto max_entries = method.max_row_entries(mesh, options);
    const std::size_t block_size = block_rows(max_entries, ff::active_threads());
    // Two blocks: while one is handed to the sink (written to disk, in rad-ff), the next is
    // computed.
    std::vector<FormFactorRow> block_rows_of[2];
    std::vector<FormFactorRowFacts> block_facts_of[2];
    for (int b = 0; b < 2; ++b) {
        block_rows_of[b].resize(std::min(block_size, last - first));
        block_facts_of[b].resize(block_rows_of[b].size());
    }
    auto hand_on = [&, max_entries](std::size_t block_begin, std::size_t block_end, int b) {
        auto& rows = block_rows_of[b];
        for (std::size_t i = block_begin; i < block_end; ++i) {
            auto& row = rows[i - block_begin];
            double sum = 0;
            for (const auto& entry : row) sum += entry.second;
            sum_rows += sum;
            max_row = std::max(max_row, sum);
            sink(i, row, block_facts_of[b][i - block_begin]);
            // A long row of one block must not keep its memory through the rest.
            if (row.capacity() > 4 * max_entries / 3 + 64) FormFactorRow().swap(row);
        }
    };
    tbb::task_group handing_on;
    int b = 0;
    for (std::size_t block_begin = first; block_begin < last; block_begin += block_size, b ^= 1) {
        const std::size_t block_end = std::min(last, block_begin + block_size);
        auto& rows = block_rows_of[b];
        auto& facts = block_facts_of[b];
        const auto trace_start = std::chrono::steady_clock::now();
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(block_begin, block_end, 1),
            [&](const tbb::blocked_range<std::size_t>& part) {
                auto& tally = reached.local();
                for (std::size_t i = part.begin(); i != part.end(); ++i) {
                    Rng rng(options.seed, context.stream_key[i]);
                    RayLog log{0, 0, tally.data()};
                    log.near = context.diameter[i];
                    auto& row = rows[i - block_begin];
                    row.clear();
                    rays_cast += kernel->compute_row(i, rng, row, log);
                    if (log.rays == 0) {
                        rays_cast += kBackFaceProbeRays;
                        ff::probe_back_faces(context, i, options.seed, kBackFaceProbeRays, log);
                    }
                    // A stray ray from a point a rounding error off a contact line is not a
                    // patch under something: a patch counts from 3 rays and a tenth of its
                    // own.
                    if (log.started_inside >= 3 && 10 * log.started_inside >= log.rays) {
                        started_inside += log.started_inside;
                        ++patches_started_inside;
                    }
                    facts[i - block_begin] = {
                        static_cast<float>(double(log.back_hits) / std::max(1u, log.rays)),
                        log.standard_error};
                    progress.advance(1);
                }
            });
        trace_seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - trace_start).count();
        handing_on.wait(); // the previous block is in: rows reach the sink in order
        handing_on.run(
            [&hand_on, block_begin, block_end, b] { hand_on(block_begin, block_end, b); });
    }
    handing_on.wait();
    progress.finish();
    for (std::size_t i = last; i < n; ++i) sink(i, empty_row, empty_facts);

    if (stats) {
        stats->rays_cast = rays_cast;
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->trace_seconds = trace_seconds;
        stats->mean_row_sum = last > first ? sum_rows / double(last - first) : 0;
        stats->max_row_sum = max_row;
        stats->rays_started_inside = started_inside;
        stats->patches_started_inside = patches_started_inside;
        stats->reached_front.assign(n, 0);
        stats->reached_back.assign(n, 0);
        for (const auto& tally : reached)
            for (std::size_t j = 0; j < n; ++j) {
                stats->reached_front[j] += tally[RayLog::kCountersPerPatch * j];
                stats->reached_back[j] += tally[RayLog::kCountersPerPatch * j + 1];
            }
    }
}

radfmt::FormFactorData compute_form_factors(const radfmt::MeshData& mesh,
                                            const FormFactorOptions& options,
                                            FormFactorStats* stats, RowRange range) {
    radfmt::FormFactorData ff;
    ff.patch_count = mesh.patches.size();
    ff.row_start.assign(1, 0);
    ff.back_fraction.reserve(ff.patch_count);
    compute_form_factor_rows(
        mesh, options,
        [&](std::size_t, FormFactorEntries row, const FormFactorRowFacts& facts) {
            for (const auto& [column, value] : row) {
                ff.columns.push_back(column);
                ff.values.push_back(value);
            }
            ff.row_start.push_back(ff.columns.size());
            ff.back_fraction.push_back(facts.back_fraction);
            if (facts.standard_error >= 0) ff.row_error.push_back(facts.standard_error);
        },
        stats, range);
    return ff;
}

} // namespace rad
