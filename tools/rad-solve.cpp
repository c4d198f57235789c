// rad-solve: mesh + cached form factors -> per-patch radiosity.
#include "radfmt/kinds.hpp"
#include "radiosity/cli.hpp"
#include "radiosity/solver.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

namespace {

struct Override {
    std::string material;
    radfmt::Rgb value;
};

Override parse_override(const std::string& spec, const char* option) {
    const auto eq = spec.find('=');
    Override o{};
    if (eq == std::string::npos || eq == 0)
        throw rad::InputError(std::string(option) + ": '" + spec + "' is not MATERIAL=r,g,b");
    o.material = spec.substr(0, eq);
    std::stringstream parts(spec.substr(eq + 1));
    std::string item;
    int count = 0;
    while (std::getline(parts, item, ',')) {
        if (count == 3)
            throw rad::InputError(std::string(option) + ": '" + spec + "' has more than 3 values");
        if (!rad::parse_number(item, o.value[count]))
            throw rad::InputError(std::string(option) + ": '" + item + "' in '" + spec +
                                  "' is not a number");
        if (!std::isfinite(o.value[count]) || o.value[count] < 0)
            throw rad::InputError(std::string(option) +
                                  ": values must be finite and non-negative in '" + spec + "'");
        ++count;
    }
    if (count == 1)
        o.value = {o.value[0], o.value[0], o.value[0]};
    else if (count != 3)
        throw rad::InputError(std::string(option) + ": '" + spec + "' needs 1 or 3 values");
    return o;
}

std::string rgb_text(const radfmt::Rgb& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", v[0], v[1], v[2]);
    return text;
}

// "out/iter-%d.rad" with the iteration number substituted.
std::string snapshot_path(const std::string& pattern, long iteration) {
    const auto pos = pattern.find("%d");
    if (pos == std::string::npos)
        throw rad::InputError("--snapshot pattern '" + pattern + "' has no %d");
    return pattern.substr(0, pos) + std::to_string(iteration) + pattern.substr(pos + 2);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Solve B_i = E_i + rho_i sum_j F_ij B_j per RGB channel from a cached form-factor\n"
        "file and write the per-patch radiosity. Materials can be overridden at solve time,\n"
        "so new light colours or reflectances never need rad-ff again."};
    std::string mesh_path, ff_path, output, method = "gs", log_path, snapshot, snapshot_at;
    std::vector<std::string> emission_overrides, reflectance_overrides;
    double emission_scale = 1, tolerance = 1e-6, row_tolerance = 0.01, sweeps = 0;
    long iterations = 0;
    long snapshot_every = 0;
    bool force = false, quiet = false, verbose = false;
    app.add_option("MESH", mesh_path, "Patch mesh from rad-mesh")->required();
    app.add_option("FORMFACTORS", ff_path, "Form-factor file from rad-ff for this mesh")
        ->required();
    app.add_option("-o,--output", output, "Output radiosity file")->required();
    app.add_option("--method", method,
                   "gs: Gauss-Seidel (the paper's); jacobi; pr: progressive refinement (one "
                   "iteration = one shot); apr: pr plus the ambient term for display")
        ->capture_default_str()
        ->check(CLI::IsMember({"gs", "jacobi", "pr", "apr"}));
    app.add_option("--iterations", iterations,
                   "Stop after N iterations (sweeps for gs/jacobi, shots for pr/apr); given "
                   "without --tolerance, exactly N are run");
    app.add_option("--sweeps", sweeps,
                   "pr/apr: stop after this many sweeps-equivalent (x patches shots)");
    app.add_option("--tolerance", tolerance,
                   "Stop when the relative change of a sweep (gs/jacobi) or the unshot power "
                   "fraction (pr/apr) falls below this")
        ->capture_default_str();
    app.add_option("--log", log_path,
                   "Write iteration,residual,power_r,power_g,power_b,seconds as CSV");
    app.add_option("--snapshot", snapshot,
                   "Write the state after chosen iterations to this pattern (with %d)");
    app.add_option("--snapshot-at", snapshot_at,
                   "Comma-separated iterations to snapshot, e.g. 1,4,10");
    app.add_option("--snapshot-every", snapshot_every, "Snapshot every k iterations");
    app.add_option("--emission", emission_overrides,
                   "Override a material's exitance: MATERIAL=r,g,b (W/m^2)");
    app.add_option("--reflectance", reflectance_overrides,
                   "Override a material's reflectance: MATERIAL=r,g,b");
    app.add_option("--emission-scale", emission_scale, "Scale every emission")
        ->capture_default_str();
    app.add_option("--row-sum-tolerance", row_tolerance,
                   "Warn when a form-factor row sums above 1 + this")
        ->capture_default_str();
    app.add_flag("--force", force,
                 "Solve even with a reflectance >= 1 (convergence not guaranteed)");
    app.add_flag("-q,--quiet", quiet, "No summary");
    app.add_flag("-v,--verbose", verbose, "Log every iteration to stderr");
    if (int rc = rad::parse_arguments(app, argc, argv); rc >= 0) return rc;

    return rad::run_tool("rad-solve", [&] {
        radfmt::Header mesh_header, ff_header;
        auto mesh = radfmt::read_mesh(mesh_path, &mesh_header);
        const auto ff = radfmt::read_form_factors(ff_path, &ff_header);
        const auto mesh_geometry = mesh.geometry_hash();
        const auto* recorded = ff_header.find("mesh_geometry_hash");
        if (!recorded || *recorded != mesh_geometry || ff.patch_count != mesh.patches.size())
            throw rad::InputError(ff_path + " is stale: it was computed for a mesh with geometry " +
                                  (recorded ? *recorded : std::string("(unknown)")) + " and " +
                                  std::to_string(ff.patch_count) + " patches, but " + mesh_path +
                                  " has " + mesh_geometry + " and " +
                                  std::to_string(mesh.patches.size()) + " patches; run rad-ff on " +
                                  mesh_path + " again");

        radfmt::Header header;
        auto find_material = [&](const std::string& name) -> radfmt::Material& {
            for (auto& m : mesh.materials)
                if (m.name == name) return m;
            std::string known;
            for (const auto& m : mesh.materials) known += (known.empty() ? "" : ", ") + m.name;
            throw rad::InputError("no material '" + name + "' in " + mesh_path +
                                  " (it has: " + known + ")");
        };
        for (const auto& spec : emission_overrides) {
            const auto o = parse_override(spec, "--emission");
            find_material(o.material).emission = o.value;
            header.set("override.emission." + o.material, rgb_text(o.value));
        }
        for (const auto& spec : reflectance_overrides) {
            const auto o = parse_override(spec, "--reflectance");
            find_material(o.material).reflectance = o.value;
            header.set("override.reflectance." + o.material, rgb_text(o.value));
        }
        if (!(emission_scale >= 0) || !std::isfinite(emission_scale))
            throw rad::InputError("--emission-scale must be finite and non-negative");
        if (emission_scale != 1) {
            for (auto& m : mesh.materials)
                for (auto& e : m.emission) e *= emission_scale;
            char scale[32];
            std::snprintf(scale, sizeof scale, "%.9g", emission_scale);
            header.set("override.emission_scale", scale);
        }
        bool any_emitter = false;
        for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
            const auto& m = mesh.materials[mesh.patches[p].material];
            for (int c = 0; c < 3; ++c) {
                if (m.reflectance[c] >= 1 && !force)
                    throw rad::InputError(
                        "material '" + m.name + "' has reflectance " + rgb_text(m.reflectance) +
                        ": a channel >= 1 may not converge (use --force to solve anyway)");
                any_emitter = any_emitter || m.emission[c] > 0;
            }
        }
        if (!any_emitter)
            std::cerr << "rad-solve: warning: no patch emits light: the result is black\n";
        std::size_t heavy_rows = 0;
        double heaviest = 0;
        for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
            double sum = 0;
            for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k) sum += ff.values[k];
            if (sum > 1 + row_tolerance) ++heavy_rows;
            heaviest = std::max(heaviest, sum);
        }
        if (heavy_rows)
            std::cerr << "rad-solve: warning: " << heavy_rows << " form-factor row(s) of "
                      << ff_path << " sum above 1 + " << row_tolerance << " (largest " << heaviest
                      << "): the form factors are inaccurate; use more samples or rays\n";

        rad::SolveOptions options;
        options.method = rad::parse_solve_method(method);
        const bool progressive = options.method == rad::SolveMethod::Progressive ||
                                 options.method == rad::SolveMethod::ProgressiveAmbient;
        if (sweeps > 0) {
            if (!progressive)
                throw rad::InputError(
                    "--sweeps applies to pr and apr; use --iterations for gs/jacobi");
            iterations = static_cast<long>(std::ceil(sweeps * double(mesh.patches.size())));
        }
        options.max_iterations = iterations;
        const bool tolerance_given = app.count("--tolerance") > 0;
        options.tolerance = (iterations > 0 && !tolerance_given) ? 0 : tolerance;
        if (options.max_iterations == 0)
            options.max_iterations =
                progressive ? 1000 * static_cast<long>(mesh.patches.size()) : 100000;

        std::set<long> snapshot_iterations;
        {
            std::stringstream parts(snapshot_at);
            std::string item;
            while (std::getline(parts, item, ',')) {
                try {
                    snapshot_iterations.insert(std::stol(item));
                } catch (...) {
                    throw rad::InputError("--snapshot-at: '" + item +
                                          "' is not an iteration number");
                }
            }
        }
        if (!snapshot.empty() && snapshot_iterations.empty() && snapshot_every <= 0)
            throw rad::InputError("--snapshot needs --snapshot-at or --snapshot-every");
        if (snapshot.empty() && (!snapshot_iterations.empty() || snapshot_every > 0))
            throw rad::InputError("--snapshot-at/--snapshot-every need --snapshot PATTERN");
        if (!snapshot.empty()) snapshot_path(snapshot, 0); // validates the pattern early

        header.tool = rad::tool_version("rad-solve");
        header.command = rad::command_line(argc, argv);
        header.provenance = ff_header.chain();
        header.inputs.push_back({mesh_path, mesh_header.file_hash});
        header.inputs.push_back({ff_path, ff_header.file_hash});
        header.set("method", method);
        header.set("mesh_geometry_hash", mesh_geometry);
        header.set("form_factor_hash", ff_header.body_hash);

        const auto problem = rad::make_problem(mesh, ff);
        std::ostringstream log;
        log << "iteration,residual,power_r,power_g,power_b,seconds\n";
        // Only observe iterations when asked to: for pr/apr the callback costs a copy of the
        // displayed state and a power sum per shot.
        if (!log_path.empty() || verbose || !snapshot.empty())
            options.on_iteration = [&](const rad::IterationRecord& r,
                                       const std::vector<radfmt::Rgb>& b) {
                char line[200];
                std::snprintf(line, sizeof line, "%ld,%.9g,%.9g,%.9g,%.9g,%.6f\n", r.iteration,
                              r.residual, r.power[0], r.power[1], r.power[2], r.seconds);
                if (!log_path.empty()) log << line;
                if (verbose) std::cerr << "rad-solve: " << line;
                if (!snapshot.empty() &&
                    (snapshot_iterations.count(r.iteration) ||
                     (snapshot_every > 0 && r.iteration % snapshot_every == 0))) {
                    auto snap = header;
                    snap.set("iterations", std::to_string(r.iteration));
                    snap.set("snapshot", "yes");
                    radfmt::write_radiosity(snapshot_path(snapshot, r.iteration), snap, {b});
                }
            };
        const auto result = rad::solve(problem, options);
        header.set("iterations", std::to_string(result.iterations));
        char residual[32];
        std::snprintf(residual, sizeof residual, "%.6g", result.residual);
        header.set(progressive ? "unshot_fraction" : "residual", residual);
        radfmt::write_radiosity(output, header, {result.radiosity});
        if (!log_path.empty()) {
            const auto text = log.str();
            radfmt::write_atomically(log_path, [&](const std::filesystem::path& temp) {
                std::ofstream out(temp);
                out << text;
                if (!(out.flush())) throw rad::InputError(log_path + ": cannot write");
            });
        }
        if (!quiet) {
            const auto power = rad::total_power(problem.area, result.radiosity);
            std::fprintf(stderr, "rad-solve: %s, %ld %s, %s %.3g%s, power %.6g %.6g %.6g W\n",
                         method.c_str(), result.iterations, progressive ? "shots" : "sweeps",
                         progressive ? "unshot fraction" : "residual", result.residual,
                         options.tolerance > 0 && !result.converged
                             ? " (not converged: iteration limit)"
                             : "",
                         power[0], power[1], power[2]);
        }
        return 0;
    });
}
