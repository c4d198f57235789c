// rad-solve: mesh + cached form factors -> per-patch radiosity.
#include "radfmt/chain.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/error.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/huge_pages.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/sky_patches.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/solver.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <set>
#include <sstream>

namespace {
// A solution with a non-finite value is never written: the first such patch, named.
void check_finite_solution(const rad::Channels& radiosity, const radfmt::MeshData& mesh) {
    for (std::size_t i = 0; i < radiosity.patches(); ++i)
        for (std::size_t c = 0; c < radiosity.channels; ++c)
            if (!std::isfinite(radiosity.at(i, c))) {
                const auto& p = mesh.patches[i];
                throw rad::InputError(
                    "patch " + std::to_string(i) + " (material '" +
                    mesh.materials[p.material].name + "', group '" + mesh.groups[p.group] +
                    "') has a radiosity that is not a finite number after the solve: the "
                    "emission and reflectance with the form factors overflow (smaller "
                    "--emission, reflectances under 1); nothing was written");
            }
}

// "out/iter-%d.rad" with the iteration number substituted.
std::string snapshot_path(const std::string& pattern, long iteration) {
    const auto pos = pattern.find("%d");
    if (pos == std::string::npos)
        throw rad::InputError("--snapshot pattern '" + pattern + "' has no %d");
    return pattern.substr(0, pos) + std::to_string(iteration) + pattern.substr(pos + 2);
}

std::set<long> parse_iteration_list(const std::string& text) {
    std::set<long> out;
    std::stringstream parts(text);
    std::string item;
    while (std::getline(parts, item, ',')) {
        std::size_t used = 0;
        long value = -1;
        try {
            value = std::stol(item, &used);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != item.size() || value < 1)
            throw rad::InputError("--snapshot-at: '" + item +
                                  "' is not an iteration number (1 or more)");
        out.insert(value);
    }
    return out;
}

// F as rad-ff wrote it: a form-factor matrix (kept packed when it holds hit counts, 3 bytes
// a non-zero against 8, decoded per row) or a link hierarchy.
struct Transport {
    radfmt::FormFactorData matrix;
    radfmt::LinkData links;
    radfmt::Header header;
    bool hierarchical = false;
    std::string geometry_hash;
};

Transport read_transport(const std::string& ff_path, const std::string& mesh_path,
                         const radfmt::MeshData& mesh) {
    Transport t;
    t.hierarchical = radfmt::read_header(ff_path).kind == radfmt::Kind::Links;
    if (t.hierarchical)
        t.links = radfmt::read_links(ff_path, &t.header);
    else
        t.matrix = radfmt::read_form_factors(ff_path, &t.header, radfmt::FormFactorLayout::compact);
    t.geometry_hash = radfmt::require_same_geometry(
        ff_path, t.header, t.hierarchical ? t.links.patch_count : t.matrix.patch_count, mesh_path,
        mesh, "run rad-ff on " + mesh_path + " again");
    return t;
}

// What the command line says.
struct SolveArgs {
    std::string mesh_path, ff_path, output, log_path, snapshot, snapshot_at, direct_path;
    std::string max_memory;
    rad::SolveRequest request;
    long snapshot_every = 0;
    bool quiet = false, verbose = false, light_groups = false;
    std::vector<std::string> group_specs;
    CLI::Option* tolerance_option = nullptr;
};

// The files, the method and when it stops.
void add_solve_options(CLI::App& app, SolveArgs& a) {
    std::string method_help;
    for (const auto* s : rad::solvers())
        method_help += std::string(method_help.empty() ? "" : "; ") + std::string(s->name()) +
                       ": " + std::string(s->summary());
    auto& request = a.request;
    app.add_option("MESH", a.mesh_path, "Patch mesh from rad-mesh")->required();
    app.add_option("FORMFACTORS", a.ff_path,
                   "Form-factor file (or links file, rad-ff --method hierarchical) from rad-ff for "
                   "this mesh")
        ->required();
    app.add_option("-o,--output", a.output, "Output radiosity file")->required();
    app.add_option("--method", request.method, method_help)
        ->capture_default_str()
        ->check(CLI::IsMember(rad::solver_names()));
    app.add_option("--iterations", request.iterations,
                   "Stop after N iterations (sweeps for gs/jacobi, shots for pr/apr); given "
                   "without --tolerance, exactly N are run")
        ->check(CLI::Range(0L, 1000000000000L));
    app.add_option("--sweeps", request.sweeps,
                   "pr/apr: stop after this many sweeps-equivalent (x patches shots)")
        ->check(rad::tool::finite_range(0, 1e6));
    a.tolerance_option =
        app.add_option("--tolerance", request.tolerance,
                       "Stop when the relative change of a sweep (gs/jacobi) or the unshot power "
                       "fraction (pr/apr) falls below this")
            ->capture_default_str()
            ->check(rad::tool::finite_range(0, 1));
}

// The log and the snapshots.
void add_record_options(CLI::App& app, SolveArgs& a) {
    app.add_option("--log", a.log_path,
                   "Write iteration,residual,power_r,power_g,power_b,seconds as CSV");
    app.add_option("--snapshot", a.snapshot,
                   "Write the state after chosen iterations to this pattern (with %d)");
    app.add_option("--snapshot-at", a.snapshot_at,
                   "Comma-separated iterations to snapshot, e.g. 1,4,10");
    app.add_option("--snapshot-every", a.snapshot_every, "Snapshot every k iterations")
        ->check(CLI::Range(0L, 1000000000000L));
}

// Materials overridden at solve time, light groups and the rest.
void add_material_options(CLI::App& app, SolveArgs& a) {
    auto& request = a.request;
    app.add_option("--emission", request.emission_overrides,
                   "Override a material's exitance: MATERIAL=r,g,b (W/m^2); a name no material "
                   "has but a group has (an OBJ's g or o name) lights that group's patches");
    app.add_option("--reflectance", request.reflectance_overrides,
                   "Override a material's reflectance: MATERIAL=r,g,b");
    app.add_option("--emission-scale", request.emission_scale, "Scale every emission")
        ->capture_default_str();
    app.add_option("--row-sum-tolerance", request.row_sum_tolerance,
                   "Warn when a form-factor row sums above 1 + this")
        ->capture_default_str();
    app.add_flag("--light-groups", a.light_groups,
                 "Solve each light group on its own, in one run (a multi-channel solve that "
                 "reads each row of F once), and store every group's radiosity, so that "
                 "rad-shade --mix can switch, dim and recolour them without another solve. A "
                 "group is each emitting material unless --group says otherwise");
    app.add_option("--group", a.group_specs,
                   "Define a light group: NAME=MATERIAL[,MATERIAL...] (repeatable; implies "
                   "--light-groups; emitting materials in no group get one each)");
    app.add_option("--direct", a.direct_path,
                   "Light that is not a glowing patch, as the first bounce: luminaires from "
                   "rad-ff --luminaires (.lum), one light group per layout group; or the sky "
                   "from rad-ff --sky (.sky), one light group per sky patch and the ground "
                   "(daylight coefficients for rad-gather --sky and --epw). Implies "
                   "--light-groups");
    app.add_flag("--force", request.force,
                 "Solve even with a reflectance >= 1 (convergence not guaranteed)");
    rad::tool::add_common_options(
        app, {.quiet = &a.quiet,
              .verbose = &a.verbose,
              .verbose_help = "Log every iteration to stderr",
              .max_memory = &a.max_memory,
              .max_memory_refuses = "light groups whose channels over the patches are"});
}

// Which iterations are written as snapshots, and where.
struct Snapshots {
    std::string pattern;
    std::set<long> at;
    long every = 0;
    bool wanted(long iteration) const {
        return !pattern.empty() && (at.count(iteration) || (every > 0 && iteration % every == 0));
    }
};

Snapshots parse_snapshots(const SolveArgs& a) {
    if (!a.snapshot.empty()) snapshot_path(a.snapshot, 0); // validates the pattern first
    return {a.snapshot, parse_iteration_list(a.snapshot_at), a.snapshot_every};
}

void check_snapshots(const Snapshots& snapshots) {
    if (!snapshots.pattern.empty() && snapshots.at.empty() && snapshots.every <= 0)
        throw rad::InputError("--snapshot needs --snapshot-at or --snapshot-every");
    if (snapshots.pattern.empty() && (!snapshots.at.empty() || snapshots.every > 0))
        throw rad::InputError("--snapshot-at/--snapshot-every need --snapshot PATTERN");
}

// The power of a state as RGB: with groups, their sum.
std::array<double, 3> rgb_power(const std::vector<double>& power) {
    std::array<double, 3> sum{0, 0, 0};
    for (std::size_t c = 0; c < power.size(); ++c) sum[c % 3] += power[c];
    return sum;
}

// What each iteration is told to: a line of the log (kept in `log`) and of --verbose, and
// the snapshot when one is wanted (the displayed state is made only then).
std::function<void(const rad::IterationRecord&, const std::function<rad::Channels()>&)>
iteration_observer(const SolveArgs& a, const Snapshots& snapshots, const radfmt::Header& header,
                   const std::vector<rad::LightGroup>& groups, std::ostringstream& log) {
    return [&a, &snapshots, &header, &groups,
            &log](const rad::IterationRecord& r, const std::function<rad::Channels()>& displayed) {
        char line[200];
        const auto power = rgb_power(r.power);
        std::snprintf(line, sizeof line, "%ld,%.9g,%.9g,%.9g,%.9g,%.6f\n", r.iteration, r.residual,
                      power[0], power[1], power[2], r.seconds);
        if (!a.log_path.empty()) log << line;
        if (a.verbose) std::cerr << "rad-solve: " << line;
        if (!snapshots.wanted(r.iteration)) return;
        auto snap = header;
        snap.set("iterations", std::to_string(r.iteration));
        snap.set("snapshot", "yes");
        radfmt::write_radiosity(snapshot_path(snapshots.pattern, r.iteration), snap,
                                rad::radiosity_data(displayed(), groups));
    };
}

void write_log(const std::string& log_path, const std::string& text) {
    radfmt::write_atomically(log_path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp);
        out << text;
        out.close(); // a full disk may only show when the last bytes go out
        if (out.fail())
            throw rad::SystemError(log_path + ": cannot write: " + std::strerror(errno));
    });
}

void print_summary(const SolveArgs& a, const rad::Solver& solver, const rad::SolveResult& result,
                   const rad::SolveControl& control, const std::array<double, 3>& power,
                   const std::vector<rad::LightGroup>& groups, double metres_per_unit) {
    if (a.quiet) return;
    const double lumens =
        rad::lux(radfmt::Rgb{{power[0], power[1], power[2]}}) * metres_per_unit * metres_per_unit;
    std::fprintf(
        stderr, "rad-solve: %s, %ld %s, %s %.3g%s, power %.6g %.6g %.6g W (%.6g lm)\n",
        a.request.method.c_str(), result.iterations, solver.shooting() ? "shots" : "sweeps",
        solver.shooting() ? "unshot fraction" : "residual", result.residual,
        control.tolerance > 0 && !result.converged ? " (not converged: iteration limit)" : "",
        power[0], power[1], power[2], lumens);
    if (groups.empty()) return;
    // A sky's 146 (or 2306) groups: the first few and the last, not a screenful.
    constexpr std::size_t kNamed = 12;
    std::string names;
    for (std::size_t k = 0; k < groups.size(); ++k) {
        if (groups.size() > kNamed && k == kNamed - 2) {
            names += " ... " + groups.back().name;
            break;
        }
        names += " " + groups[k].name;
    }
    std::fprintf(stderr, "rad-solve: %zu light group(s):%s\n", groups.size(), names.c_str());
}

// Warnings about the transport (row sums, unlit or wrongly facing groups), before solving.
void warn_transport(const SolveArgs& a, const radfmt::MeshData& mesh, const Transport& transport) {
    const auto warnings =
        transport.hierarchical
            ? rad::solve_warnings(mesh, transport.links, transport.header, a.ff_path,
                                  a.request.row_sum_tolerance)
            : rad::solve_warnings(mesh, transport.matrix, a.ff_path, a.request.row_sum_tolerance);
    for (const auto& warning : warnings)
        if (a.direct_path.empty() || warning.rfind("no patch emits", 0) != 0)
            std::cerr << "rad-solve: warning: " << warning << '\n';
}

// The channels a solve holds grow with its light groups (a layout of 1000 luminaires, each its
// own group): the emission, the solution and the solver's working copy of them, and the file's
// per-group radiosity and its sum, estimated before solving.
void check_channel_memory(const SolveArgs& a, const rad::Channels& emission) {
    const double bytes = double(emission.values.size()) * sizeof(double) * 5;
    const auto limit = rad::tool::memory_limit(a.max_memory);
    if (bytes <= double(limit)) return;
    throw rad::InputError(std::to_string(emission.channels / 3) + " light group(s) over " +
                          std::to_string(emission.patches()) + " patches need about " +
                          rad::human_bytes(bytes) + ", more than " +
                          rad::tool::memory_limit_text(a.max_memory) +
                          " (join groups: a layout's group column or --group; or a larger "
                          "--max-memory)");
}

// Whether a group of `groups` has this name.
bool group_named(const std::vector<rad::LightGroup>& groups, const std::string& name) {
    return std::any_of(groups.begin(), groups.end(),
                       [&](const rad::LightGroup& g) { return g.name == name; });
}

// The channels of light that is not a glowing patch (--direct): `count` groups first, each
// patch emitting rho x `irradiance(patch, group)` (the first bounce), then the `others`
// material groups' channels that `emission` holds (none: empty).
template <class Irradiance>
rad::Channels first_bounce_groups(const radfmt::MeshData& mesh, std::size_t count,
                                  Irradiance&& irradiance, std::size_t others,
                                  const rad::Channels& emission) {
    rad::Channels e(mesh.patches.size(), 3 * (count + others));
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& rho = mesh.materials[mesh.patches[i].material].reflectance;
        for (std::size_t g = 0; g < count; ++g) {
            const radfmt::Rgb d = irradiance(i, g);
            for (std::size_t c = 0; c < 3; ++c) e.at(i, 3 * g + c) = rho[c] * d[c];
        }
        for (std::size_t c = 0; c < 3 * others; ++c) e.at(i, 3 * count + c) = emission.at(i, c);
    }
    return e;
}

// Groups named `names` (of no material) put before `groups`, in that order.
void put_groups_first(const std::vector<std::string>& names, std::vector<rad::LightGroup>& groups) {
    std::vector<rad::LightGroup> all;
    for (const auto& name : names) all.push_back({name, {}});
    all.insert(all.end(), groups.begin(), groups.end());
    groups = std::move(all);
}

// --direct: the luminaires' groups first, each emitting rho x its direct irradiance (the first
// bounce), then the material groups `emission` holds (none: empty). Says the luminaires' flux.
rad::Channels add_direct_light(const SolveArgs& a, const radfmt::MeshData& mesh,
                               const radfmt::Header& mesh_header, radfmt::Header& header,
                               std::vector<rad::LightGroup>& groups, rad::Channels emission) {
    radfmt::Header lum_header;
    const auto lum = radfmt::read_luminaires(a.direct_path, &lum_header);
    radfmt::require_same_geometry(a.direct_path, lum_header, lum.patch_count, a.mesh_path, mesh,
                                  "run rad-ff --luminaires on " + a.mesh_path + " again");
    for (const auto& name : lum.groups)
        if (group_named(groups, name))
            throw rad::InputError(a.direct_path + ": light group '" + name +
                                  "' is also an emitting material's group: name the "
                                  "layout's group differently");
    auto e = first_bounce_groups(
        mesh, lum.groups.size(), [&](std::size_t i, std::size_t g) { return lum.of(i, g); },
        groups.size(), emission);
    for (const auto& name : lum.groups)
        header.set("light_group." + name, "luminaires of " + a.direct_path);
    put_groups_first(lum.groups, groups);
    header.set("direct", a.direct_path);
    if (!a.quiet) {
        const auto set = rad::build_luminaires({lum.layout_name, lum.layout_text, lum.files},
                                               rad::metres_per_unit(mesh_header));
        double emitted = 0;
        for (const auto& l : set.luminaires) emitted += set.flux(l);
        std::fprintf(stderr,
                     "rad-solve: %zu luminaire(s) in %zu light group(s): %.6g lm (%.6g W "
                     "at %g lm/W)\n",
                     set.luminaires.size(), lum.groups.size(), emitted,
                     emitted / rad::kRadianceEfficacy, rad::kRadianceEfficacy);
    }
    return e;
}

// --direct with a .sky: one group per sky patch (and the ground) at unit radiance, each
// emitting rho x its irradiance on the patch, then the material groups `emission` holds.
rad::Channels add_sky_light(const SolveArgs& a, const radfmt::MeshData& mesh,
                            radfmt::Header& header, std::vector<rad::LightGroup>& groups,
                            rad::Channels emission) {
    radfmt::Header sky_header;
    const auto sky = radfmt::read_sky(a.direct_path, &sky_header);
    radfmt::require_same_geometry(a.direct_path, sky_header, sky.patch_count, a.mesh_path, mesh,
                                  "run rad-ff --sky on " + a.mesh_path + " again");
    const auto patches = rad::SkyPatches::parse(sky.subdivision);
    if (patches.count() != sky.sky_patches)
        throw rad::InputError(a.direct_path + ": " + std::to_string(sky.sky_patches) +
                              " sky patches, but " + sky.subdivision + " has " +
                              std::to_string(patches.count()));
    const std::size_t sky_groups = sky.sky_patches;
    std::vector<std::string> names;
    for (std::size_t s = 0; s < sky_groups; ++s) names.push_back(patches.name(s));
    for (const auto& g : groups)
        if (std::find(names.begin(), names.end(), g.name) != names.end())
            throw rad::InputError("light group '" + g.name +
                                  "' is also a sky patch's name: name it differently");
    auto e = first_bounce_groups(
        mesh, sky_groups, [&](std::size_t i, std::size_t s) { return sky.of(i, s); }, groups.size(),
        emission);
    put_groups_first(names, groups);
    header.set("direct", a.direct_path);
    header.set("sky_subdivision", sky.subdivision);
    header.set("north", sky_header.get("north", a.direct_path));
    if (!a.quiet)
        std::fprintf(stderr,
                     "rad-solve: daylight: %zu light groups, one per sky patch of %s and the "
                     "ground, each at a radiance of 1 W/m^2/sr (any sky or hour is a mix of "
                     "them: rad-gather --sky, --epw)\n",
                     sky_groups, sky.subdivision.c_str());
    return e;
}

int solve(SolveArgs& a, int argc, char** argv) {
    const auto snapshots = parse_snapshots(a);
    rad::tool::check_outputs(
        {a.mesh_path, a.ff_path, a.direct_path}, {{"-o", a.output}, {"--log", a.log_path}},
        {{"--snapshot", a.snapshot, [&](long iteration) { return snapshots.wanted(iteration); }}});
    // All outputs (the result, the log, every snapshot) land together or not at all.
    radfmt::OutputBatch outputs;
    auto& request = a.request;
    request.tolerance_given = a.tolerance_option->count() > 0;
    const auto& solver = rad::solver(request.method);
    if (a.verbose) std::cerr << "rad-solve: pages: " << rad::huge_pages_state() << '\n';
    radfmt::Header mesh_header;
    auto mesh = radfmt::read_mesh(a.mesh_path, &mesh_header);
    // The materials first: a refusal comes before the (large) form factors are read. The
    // override fields are kept to go into the header once it exists.
    radfmt::Header overrides;
    std::vector<std::string> notes;
    rad::apply_material_overrides(mesh, request, overrides, &notes);
    if (!a.quiet)
        for (const auto& note : notes) std::fprintf(stderr, "rad-solve: %s\n", note.c_str());
    rad::check_reflectances(mesh, request.force);
    const auto transport = read_transport(a.ff_path, a.mesh_path, mesh);
    if (transport.hierarchical && solver.shooting())
        throw rad::InputError(a.ff_path +
                              " holds links (rad-ff --method hierarchical): pr and apr shoot "
                              "along rows of F, which links do not have; use --method gs or "
                              "jacobi");

    std::vector<radfmt::Parent> parents{{a.mesh_path, &mesh_header},
                                        {a.ff_path, &transport.header}};
    // The light sources' file: its own ancestors join the provenance (its rad-ff --luminaires
    // or --sky beside the form factors' rad-ff); its hash from the whole file on disk.
    radfmt::Header direct_header;
    if (!a.direct_path.empty()) {
        direct_header = radfmt::read_header(a.direct_path);
        direct_header.file_hash = radfmt::hash_file(a.direct_path);
        parents.push_back({a.direct_path, &direct_header});
    }
    auto header = radfmt::derived_header(rad::tool_version("rad-solve"),
                                         radfmt::command_line(argc, argv), parents);
    for (const auto& [key, value] : overrides.fields) header.set(key, value);
    warn_transport(a, mesh, transport);
    auto control = rad::stop_rule(solver, request, mesh.patches.size());
    check_snapshots(snapshots);
    rad::record_solve_inputs(header, request, transport.geometry_hash, transport.header);

    const auto op = transport.hierarchical ? rad::make_operator(mesh, transport.links)
                                           : rad::make_operator(mesh, transport.matrix);
    std::vector<rad::LightGroup> groups;
    if (a.light_groups || !a.group_specs.empty() ||
        (!a.direct_path.empty() && rad::any_emitter(mesh))) {
        groups = rad::light_groups(mesh, a.group_specs);
        rad::record_light_groups(header, mesh, groups);
    }
    auto emission = groups.empty() ? rad::emission_of(mesh) : rad::grouped_emission(mesh, groups);
    const bool sky =
        !a.direct_path.empty() && radfmt::read_header(a.direct_path).kind == radfmt::Kind::Sky;
    if (sky)
        emission = add_sky_light(a, mesh, header, groups,
                                 groups.empty() ? rad::Channels() : std::move(emission));
    else if (!a.direct_path.empty())
        emission = add_direct_light(a, mesh, mesh_header, header, groups,
                                    groups.empty() ? rad::Channels() : std::move(emission));
    std::ostringstream log;
    log << "iteration,residual,power_r,power_g,power_b,seconds\n";
    // Only observe iterations when asked to (a line per shot for pr/apr).
    if (!a.log_path.empty() || a.verbose || !a.snapshot.empty())
        control.on_iteration = iteration_observer(a, snapshots, header, groups, log);
    check_channel_memory(a, emission);
    const auto result = solver.solve(op, emission, control);
    rad::record_solve_result(header, solver, result);
    check_finite_solution(result.radiosity, mesh);
    radfmt::write_radiosity(a.output, header, rad::radiosity_data(result.radiosity, groups));
    if (!a.log_path.empty()) write_log(a.log_path, log.str());
    outputs.commit();
    print_summary(a, solver, result, control,
                  rgb_power(rad::total_power(op.area, result.radiosity)), groups,
                  rad::metres_per_unit(mesh_header));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Solve B_i = E_i + rho_i sum_j F_ij B_j per RGB channel from a cached form-factor\n"
        "file and write the per-patch radiosity. Materials can be overridden at solve time,\n"
        "so new light colours or reflectances never need rad-ff again."};
    SolveArgs args;
    add_solve_options(app, args);
    add_record_options(app, args);
    add_material_options(app, args);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::restart_with_huge_pages(argv);
    return rad::tool::run_tool("rad-solve", [&] { return solve(args, argc, argv); });
}
