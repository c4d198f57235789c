// How long a form-factor run will take, measured before it starts: a few of its rows,
// spread over the range, computed on one thread, their mean cost times the rows over the
// threads (rows cost about the same: the row loop is balanced over threads).
#include "formfactor/sampling.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/formfactor_method.hpp"

#include <algorithm>
#include <chrono>

namespace rad {

FormFactorEstimate estimate_form_factor_time(const radfmt::MeshData& mesh,
                                             const FormFactorOptions& options_in, RowRange range,
                                             double budget_seconds) {
    using clock = std::chrono::steady_clock;
    const auto options = resolve_form_factor_options(options_in);
    const std::size_t n = mesh.patches.size();
    const std::size_t first = std::min<std::uint64_t>(range.begin, n);
    const std::size_t last =
        std::max(first, static_cast<std::size_t>(std::min<std::uint64_t>(range.end, n)));
    FormFactorEstimate estimate;
    if (last == first) return estimate;
    const auto setup_start = clock::now();
    const RayScene scene(mesh);
    const FormFactorContext context(mesh, scene, options.specular_depth);
    const auto kernel = form_factor_method(options.method).prepare(context, options);
    estimate.setup_seconds = std::chrono::duration<double>(clock::now() - setup_start).count();

    // Rows at the van der Corput points of the range, so that stopping early still spreads
    // them; scratch counters stand for the run's per-thread tallies.
    std::vector<std::uint32_t> counters(RayLog::kCountersPerPatch * n, 0);
    FormFactorRow row;
    const auto start = clock::now();
    double elapsed = 0;
    while (estimate.sampled_rows < kEstimateMaxRows &&
           (estimate.sampled_rows < 2 || elapsed < budget_seconds)) {
        const auto at = first + static_cast<std::size_t>(
                                    ff::radical_inverse(estimate.sampled_rows, 2) * (last - first));
        Rng rng(options.seed, context.stream_key[at]);
        RayLog log{0, 0, counters.data()};
        row.clear();
        kernel->compute_row(at, rng, row, log);
        ++estimate.sampled_rows;
        elapsed = std::chrono::duration<double>(clock::now() - start).count();
    }
    const std::size_t threads = std::max(1u, ff::active_threads());
    estimate.seconds = estimate.setup_seconds + elapsed / double(estimate.sampled_rows) *
                                                    double(last - first) / double(threads);
    estimate.threads = threads;
    return estimate;
}

} // namespace rad
