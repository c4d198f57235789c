// rad-ff: patch mesh -> cached sparse form-factor matrix.
#include "radfmt/kinds.hpp"
#include "radiosity/cli.hpp"
#include "radiosity/formfactor.hpp"

#include <cstdio>
#include <iostream>

namespace {
std::uint64_t parse_size(const std::string& text) {
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (...) {
        throw rad::InputError("--max-memory: '" + text + "' is not a size (e.g. 8G, 512M)");
    }
    std::string unit = text.substr(used);
    double scale = 1;
    if (unit == "K" || unit == "KiB" || unit == "k")
        scale = 1024.0;
    else if (unit == "M" || unit == "MiB")
        scale = 1024.0 * 1024;
    else if (unit == "G" || unit == "GiB")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "T" || unit == "TiB")
        scale = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty() && unit != "B")
        throw rad::InputError("--max-memory: unknown unit '" + unit + "' (use K, M, G or T)");
    if (!(value > 0)) throw rad::InputError("--max-memory must be positive");
    return static_cast<std::uint64_t>(value * scale);
}
} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Compute the form factors F_ij between every pair of patches of a mesh (ray-cast\n"
        "visibility with Embree, rows in parallel) and write the sparse form-factor file."};
    std::string input, output, method = "analytic", max_memory;
    rad::FormFactorOptions options;
    int threads = 0;
    app.add_option("MESH", input, "Patch mesh from rad-mesh")->required();
    app.add_option("-o,--output", output, "Output form-factor file")->required();
    app.add_option("--method", method,
                   "analytic: exact point-to-polygon integral x ray visibility; pairwise: the "
                   "paper's point-pair integration of eq. 5; hemisphere: cosine-weighted rays "
                   "(scales to large scenes)")
        ->capture_default_str()
        ->check(CLI::IsMember({"analytic", "pairwise", "hemisphere"}));
    app.add_option("--samples", options.samples,
                   "Sample points per patch, rounded to a square (default: 16 for analytic, 64 "
                   "for pairwise; pairwise uses a quarter of the resolution for distant pairs)")
        ->check(CLI::Range(1, 4096));
    app.add_option("--visibility-rays", options.visibility_rays,
                   "analytic: visibility rays per sample point and patch")
        ->capture_default_str()
        ->check(CLI::Range(1, 1024));
    app.add_option("--rays", options.rays, "hemisphere: rays per patch")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000000));
    app.add_option("--seed", options.seed, "Seed for every random choice")->capture_default_str();
    app.add_option("--threads", threads, "Worker threads (0: all cores)")->capture_default_str();
    app.add_option("--max-memory", max_memory,
                   "Refuse to start when the estimated memory exceeds this (e.g. 4G; default: "
                   "80% of physical memory)");
    app.add_flag("-q,--quiet", options.quiet, "No progress and no summary");
    if (int rc = rad::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::run_tool("rad-ff", [&] {
        options.method = rad::parse_method(method);
        if (app.count("--samples") == 0)
            options.samples = options.method == rad::FormFactorMethod::Pairwise ? 64 : 16;
        const std::uint64_t limit =
            max_memory.empty() ? static_cast<std::uint64_t>(0.8 * rad::physical_memory_bytes())
                               : parse_size(max_memory);
        rad::ThreadLimit thread_limit(threads);
        radfmt::Header mesh_header;
        const auto mesh = radfmt::read_mesh(input, &mesh_header);
        if (mesh.patches.empty()) throw rad::InputError(input + ": mesh has no patches");
        const auto need = rad::estimate_form_factor_memory(mesh, options);
        if (need > limit)
            throw rad::InputError(input + ": " + method + " form factors for " +
                                  std::to_string(mesh.patches.size()) + " patches need up to " +
                                  rad::human_bytes(double(need)) + ", more than --max-memory " +
                                  rad::human_bytes(double(limit)) +
                                  " (use --method hemisphere, fewer --rays, or a coarser mesh)");

        rad::FormFactorStats stats;
        const auto ff = rad::compute_form_factors(mesh, options, &stats);

        radfmt::Header header;
        header.tool = rad::tool_version("rad-ff");
        header.command = rad::command_line(argc, argv);
        header.provenance = mesh_header.chain();
        header.inputs.push_back({input, mesh_header.file_hash});
        header.set("method", method);
        if (options.method == rad::FormFactorMethod::Hemisphere) {
            header.set("rays", std::to_string(options.rays));
        } else {
            header.set("samples", std::to_string(options.samples));
            if (options.method == rad::FormFactorMethod::Analytic)
                header.set("visibility_rays", std::to_string(options.visibility_rays));
        }
        header.set("seed", std::to_string(options.seed));
        header.set("mesh_geometry_hash", mesh.geometry_hash());
        radfmt::write_form_factors(output, header, ff);
        if (!options.quiet) {
            std::fprintf(stderr,
                         "rad-ff: %llu patches, %llu non-zeros, %llu rays in %.3f s (%.3g rays/s "
                         "while tracing, %d threads), row sums mean %.5f max %.5f\n",
                         static_cast<unsigned long long>(ff.patch_count),
                         static_cast<unsigned long long>(ff.nonzeros()),
                         static_cast<unsigned long long>(stats.rays_cast), stats.seconds,
                         stats.trace_seconds > 0 ? stats.rays_cast / stats.trace_seconds : 0.0,
                         thread_limit.threads(), stats.mean_row_sum, stats.max_row_sum);
        }
        return 0;
    });
}
