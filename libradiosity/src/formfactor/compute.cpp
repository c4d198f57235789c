// The parts every form-factor method shares: the per-mesh context, the parallel loop over
// rows with a random stream per row, and the packing of rows into sparse storage.
#include "radiosity/formfactor.hpp"
#include "radiosity/formfactor_method.hpp"
#include "radiosity/progress.hpp"
#include "sampling.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>

namespace rad {

FormFactorContext::FormFactorContext(const radfmt::MeshData& mesh_, const RayScene& scene_)
    : mesh(mesh_), scene(scene_), epsilon(scene_.epsilon()) {
    const std::size_t n = mesh.patches.size();
    polygons.reserve(n);
    diameter.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& p = mesh.patches[i];
        PatchPolygon g{};
        g.count = p.corner_count();
        for (int k = 0; k < g.count; ++k) g.corners[k] = mesh.vertices[p.corners[k]];
        for (int a = 0; a < g.count; ++a)
            for (int b = a + 1; b < g.count; ++b)
                diameter[i] = std::max(diameter[i], length(g.corners[a] - g.corners[b]));
        polygons.push_back(g);
    }
}

bool FormFactorContext::in_front(std::size_t i, std::size_t j) const {
    const auto& pi = mesh.patches[i];
    for (int k = 0; k < polygons[j].count; ++k)
        if (dot(polygons[j].corners[k] - pi.centroid, pi.normal) > epsilon) return true;
    return false;
}

FormFactorOptions resolve_form_factor_options(FormFactorOptions options) {
    form_factor_method(options.method).apply_defaults(options);
    return options;
}

std::uint64_t estimate_form_factor_memory(const radfmt::MeshData& mesh,
                                          const FormFactorOptions& options) {
    const std::uint64_t n = mesh.patches.size();
    const auto& method = form_factor_method(options.method);
    const std::uint64_t per_row = method.max_row_entries(mesh, options);
    // The threads this run will use (a ThreadLimit in force, else every core).
    const auto threads = static_cast<unsigned>(
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    // Rows are built then packed: entries (4 + 4 bytes) are held twice at the peak; Embree
    // and the mesh take a few hundred bytes per patch.
    // The back-face tallies are two counters per patch and thread.
    return 2 * n * per_row * 8 + n * 400 + mesh.vertices.size() * 64 + n * 8 * threads +
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

radfmt::FormFactorData compute_form_factors(const radfmt::MeshData& mesh,
                                            const FormFactorOptions& options_in,
                                            FormFactorStats* stats, RowRange range) {
    const auto start = std::chrono::steady_clock::now();
    const auto options = resolve_form_factor_options(options_in);
    const auto& method = form_factor_method(options.method);
    const std::size_t n = mesh.patches.size();
    const std::size_t first = std::min<std::uint64_t>(range.begin, n);
    const std::size_t last =
        std::max(first, static_cast<std::size_t>(std::min<std::uint64_t>(range.end, n)));

    const RayScene scene(mesh);
    const FormFactorContext context(mesh, scene);
    const auto kernel = method.prepare(context, options);

    std::vector<FormFactorRow> rows(n);
    std::vector<float> back_fraction(n, 0.0f);
    // Per-thread tallies of the rays reaching each patch's front and back (integer sums:
    // the totals do not depend on the threads).
    tbb::enumerable_thread_specific<std::vector<std::uint32_t>> reached(
        [n] { return std::vector<std::uint32_t>(2 * n, 0); });
    std::atomic<std::uint64_t> rays_cast{0}, started_inside{0};
    std::atomic<std::size_t> patches_started_inside{0};
    Progress progress("rad-ff " + options.method, last - first, options.quiet);
    const auto trace_start = std::chrono::steady_clock::now();
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(first, last, 1),
        [&](const tbb::blocked_range<std::size_t>& block) {
            auto& tally = reached.local();
            for (std::size_t i = block.begin(); i != block.end(); ++i) {
                Rng rng(options.seed, i);
                RayLog log{0, 0, tally.data(), tally.data() + n};
                log.near = context.diameter[i];
                rays_cast += kernel->compute_row(i, rng, rows[i], log);
                if (log.rays == 0) {
                    rays_cast += kBackFaceProbeRays;
                    ff::probe_back_faces(context, i, options.seed, kBackFaceProbeRays, log);
                }
                // A stray ray from a point a rounding error off a contact line is not a
                // patch under something: a patch counts from 3 rays and a tenth of its own.
                if (log.started_inside >= 3 && 10 * log.started_inside >= log.rays) {
                    started_inside += log.started_inside;
                    ++patches_started_inside;
                }
                back_fraction[i] =
                    static_cast<float>(double(log.back_hits) / std::max(1u, log.rays));
                progress.advance(1);
            }
        });
    const double trace_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - trace_start).count();
    progress.finish();

    radfmt::FormFactorData ff;
    ff.patch_count = n;
    ff.back_fraction = std::move(back_fraction);
    ff.row_start.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ff.row_start[i + 1] = ff.row_start[i] + rows[i].size();
    ff.columns.reserve(ff.row_start[n]);
    ff.values.reserve(ff.row_start[n]);
    double sum_rows = 0, max_row = 0;
    for (auto& row : rows) {
        double sum = 0;
        for (const auto& [col, value] : row) {
            ff.columns.push_back(col);
            ff.values.push_back(value);
            sum += value;
        }
        sum_rows += sum;
        max_row = std::max(max_row, sum);
        FormFactorRow().swap(row);
    }
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
                stats->reached_front[j] += tally[j];
                stats->reached_back[j] += tally[n + j];
            }
    }
    return ff;
}

} // namespace rad
