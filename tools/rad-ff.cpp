// rad-ff: patch mesh -> cached sparse form-factor matrix.
#include "radfmt/chain.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/formfactor_method.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/hierarchy.hpp"
#include "radiosity/huge_pages.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <cstdio>
#include <optional>
#include <string>

namespace {
// Warning lines of one kind shown without -v (the worst first).
constexpr std::size_t kMaxWarningLines = 20;
// Above this, an O(n^2) method also hears what hemisphere would cost.
constexpr double kSuggestFasterSeconds = 60;
using rad::tool::about;
using rad::tool::kSayEstimateSeconds;

// Measures the run before it starts and says what it will cost when that is long (or
// `always`); for an O(n^2) method, also what hemisphere (rays, O(n)) would cost.
void say_estimate(const radfmt::MeshData& mesh, const rad::FormFactorOptions& options,
                  rad::RowRange range, bool always) {
    const auto estimate = rad::estimate_form_factor_time(mesh, options, range);
    if (!always && estimate.seconds < kSayEstimateSeconds) return;
    const auto rows = std::min<std::uint64_t>(range.end, mesh.patches.size()) -
                      std::min<std::uint64_t>(range.begin, mesh.patches.size());
    std::string line = "rad-ff: " + options.method + ": " + about(estimate.seconds) + " for ";
    line.append(std::to_string(rows)).append(" rows on ");
    line.append(std::to_string(estimate.threads)).append(" thread(s) (measured on ");
    line.append(std::to_string(estimate.sampled_rows)).append(" rows)");
    if ((always || estimate.seconds > kSuggestFasterSeconds) && options.method != "hemisphere") {
        rad::FormFactorOptions hemisphere;
        hemisphere.method = "hemisphere";
        hemisphere.seed = options.seed;
        const auto faster = rad::estimate_form_factor_time(mesh, hemisphere, range);
        if (always || faster.seconds < estimate.seconds)
            line.append("; --method hemisphere: ").append(about(faster.seconds));
    }
    std::fprintf(stderr, "%s\n", line.c_str());
}
// --method hierarchical: the tree and its links into a links file.
// A part (--rows K/N) records its shard and the command one run would have had.
void write_hierarchical(const std::string& input, const radfmt::MeshData& mesh,
                        const radfmt::Header& mesh_header, const rad::HierarchyOptions& options,
                        const std::string& output, int argc, char** argv, bool part, bool quiet) {
    rad::HierarchyStats stats;
    const auto links = rad::compute_links(mesh, options, &stats);
    const radfmt::Parent parents[] = {{input, &mesh_header}};
    auto header = radfmt::derived_header(rad::tool_version("rad-ff"),
                                         radfmt::command_line(argc, argv), parents);
    for (const auto& [key, value] : rad::link_header_fields(options, mesh)) header.set(key, value);
    header.set("mesh_geometry_hash", mesh.geometry_hash());
    if (part) {
        header.set("shard", std::to_string(options.shard));
        header.set("shards", std::to_string(options.shards));
        header.set("unsharded_command", rad::unsharded_command(argc, argv));
    }
    radfmt::write_links(output, header, links);
    if (quiet) return;
    const double n = double(std::max<std::size_t>(1, mesh.patches.size()));
    if (part)
        std::fprintf(stderr, "rad-ff: shard %u of %u: the links of the pairs it owns\n",
                     options.shard, options.shards);
    std::fprintf(
        stderr,
        "rad-ff: hierarchical: %zu patches, %zu nodes, %llu links (%.1f a patch, %llu "
        "between two patches; %llu node pairs by contour integral), %llu pairs examined (%llu "
        "facing away), %llu rays; tree %.3f s, links %.3f s\n",
        mesh.patches.size(), links.nodes.size(), static_cast<unsigned long long>(links.links()),
        double(links.links()) / n, static_cast<unsigned long long>(stats.leaf_links),
        static_cast<unsigned long long>(stats.outline_pairs),
        static_cast<unsigned long long>(stats.pairs), static_cast<unsigned long long>(stats.culled),
        static_cast<unsigned long long>(stats.rays), stats.tree_seconds, stats.link_seconds);
}

// --rows K/N for --method hierarchical: shard K of N of the refinement's tasks (its links
// are not rows of a matrix, so A:B has no meaning there).
void set_link_shard(const std::string& rows, std::size_t patches, rad::HierarchyOptions& options) {
    if (rows.find('/') == std::string::npos)
        throw rad::InputError("--rows " + rows +
                              ": --method hierarchical is split into shards K/N (its links are "
                              "not rows), e.g. --rows 0/4");
    const auto [shard, shards] = rad::parse_shard(rows, patches);
    options.shard = static_cast<std::uint32_t>(shard);
    options.shards = static_cast<std::uint32_t>(shards);
}

// What the command line says.
struct FfArgs {
    std::string output, max_memory, rows, luminaires, sky;
    double north = 0;
    rad::FormFactorOptions options;
    rad::HierarchyOptions hierarchy;
    int threads = 0, error_batches = 8;
    std::vector<std::string> inputs;
    bool merge = false, estimate_only = false, verbose = false, error = false;
    CLI::Option *rows_option = nullptr, *output_option = nullptr, *rays_option = nullptr;
};

// The inputs, the output, sharding and merging.
void add_file_options(CLI::App& app, FfArgs& a) {
    app.add_option("MESH", a.inputs,
                   "Patch mesh from rad-mesh (with --merge: the part files to join)")
        ->required();
    a.output_option = app.add_option("-o,--output", a.output, "Output form-factor file");
    app.add_option("--luminaires", a.luminaires,
                   "A luminaire layout (CSV: name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,"
                   "maintenance,group; photometric files IES or EULUMDAT beside it): write each "
                   "luminaire's direct light on every patch to -o (a .lum file for rad-solve "
                   "--direct) instead of form factors");
    app.add_option("--sky", a.sky,
                   "A sky subdivision (reinhart:1 = Tregenza's 145 patches, reinhart:2 = 577, "
                   "reinhart:4 = 2305): write each patch's view of every sky patch and of the "
                   "ground, through openings and glass, to -o (a .sky file for rad-solve "
                   "--direct: daylight coefficients) instead of form factors");
    app.add_option("--north", a.north,
                   "With --sky: where true north is, in degrees from the scene's -Z axis "
                   "towards +X (clockwise seen from above; +Y is up)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(-360, 360));
    app.add_flag("--estimate", a.estimate_only,
                 "Measure a few rows, say how long the run would take (and, for an O(n^2) "
                 "method, what hemisphere would take), and stop: no output, no -o needed. "
                 "Without it, rad-ff says so before runs of over 10 s");
}

// --method and what each method takes.
void add_method_options(CLI::App& app, FfArgs& a) {
    std::string method_help;
    for (const auto* m : rad::form_factor_methods())
        method_help += std::string(method_help.empty() ? "" : "; ") + std::string(m->name()) +
                       ": " + std::string(m->summary());
    auto method_names = rad::form_factor_method_names();
    method_names.push_back("auto");
    method_names.push_back("hierarchical");
    method_help += "; hierarchical: links between a tree of patch blocks and clusters, O(n) "
                   "instead of n^2 (writes a links file; rad-solve --method gs or jacobi)";
    auto& options = a.options;
    options.method = "auto";
    app.add_option("--method", options.method,
                   "auto (the default): analytic up to " +
                       std::to_string(rad::kAutoAnalyticPatches) +
                       " patches, hemisphere above (analytic's pairs grow as n^2); " + method_help)
        ->capture_default_str()
        ->check(CLI::IsMember(method_names));
    app.add_option("--samples", options.samples,
                   "Sample points per patch, rounded to a square (default: 16 for analytic, 64 "
                   "for pairwise; pairwise uses a quarter of the resolution for distant pairs; "
                   "hierarchical: sample pairs and rays per link between blocks or clusters, 64)")
        ->check(CLI::Range(1, 4096));
    app.add_option("--visibility-rays", options.visibility_rays,
                   "analytic: visibility rays per sample point and patch")
        ->capture_default_str()
        ->check(CLI::Range(1, 1024));
    a.rays_option = app.add_option("--rays", options.rays,
                                   "hemisphere: rays per patch (--sky: 1000 unless given; "
                                   "sensors trace the sky themselves, the .sky feeds the "
                                   "light the room reflects)")
                        ->capture_default_str()
                        ->check(CLI::Range(1, 100000000));
    app.add_flag("--error", a.error,
                 "hemisphere: cast each row's rays in --batches independent batches and write "
                 "the row's standard error (the square root of its entries' summed variances, "
                 "from the batches' spread) into the file: rad-info shows it. The batches are "
                 "stratified each on their own, so the matrix is a little noisier than one "
                 "stratified set of the same rays");
    app.add_option("--batches", a.error_batches,
                   "--error: independent batches per row (--rays must be a multiple, at least "
                   "8 rays a batch)")
        ->capture_default_str()
        ->check(CLI::Range(2, 1024));
    app.add_option("--specular-depth", options.specular_depth,
                   "hemisphere, hemicube: how many mirrors and panes of glass a path may go "
                   "through (each "
                   "reflection or crossing counts one; paths also end where under 1e-4 of the "
                   "light would go on); for a mesh with no specular material it changes "
                   "nothing")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    app.add_option("--resolution", options.resolution,
                   "hemicube: pixels across the hemi-cube's top face, even (default " +
                       std::to_string(rad::kDefaultHemicubeResolution) + ": " +
                       std::to_string(rad::hemicube_rays(rad::kDefaultHemicubeResolution)) +
                       " rays a patch)")
        ->check(CLI::Range(2, rad::kMaxHemicubeResolution));
    app.add_option("--hemicube-origin", options.hemicube_origin,
                   "hemicube: spread (each pixel's ray from its own point of the patch: the "
                   "patch's form factor) or centre (the paper's: the form factor from the "
                   "patch's centre, aliasing small far patches)")
        ->capture_default_str()
        ->check(CLI::IsMember({"spread", "centre"}));
    app.add_option("--epsilon", a.hierarchy.epsilon,
                   "hierarchical: link two nodes when the larger of their form factors to each "
                   "other is at most this (smaller: more links, closer to the full matrix)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(1e-9, 1));
    app.add_option("--emitters", a.hierarchy.emitters,
                   "hierarchical: materials to link as emitters (finer, and finer where their "
                   "light varies over what reflects it) besides those that emit in the mesh, "
                   "comma-separated: for a lamp made to emit at solve time")
        ->delimiter(',');
}

// The seed, threads, memory, quiet, and sharding.
void add_run_options(CLI::App& app, FfArgs& a) {
    a.rows_option = rad::tool::add_common_options(
        app, {.threads = &a.threads,
              .seed = &a.options.seed,
              .seed_help = "every random choice",
              .quiet = &a.options.quiet,
              .shows_progress = true,
              .verbose = &a.verbose,
              .verbose_help = "Every warning line (without it, at most 20 of a kind, the worst "
                              "first, and a count of the rest)",
              .max_memory = &a.max_memory,
              .max_memory_refuses = "a run",
              .rows = &a.rows,
              .merge = &a.merge,
              .tool = "rad-ff",
              .rows_unit = "rows",
              .rows_extra = "; --method hierarchical: K/N only, the refinement's tasks",
              .merge_result = "the form-factor file one run of the same mesh and options "
                              "would have written"});
    app.get_option("--estimate")->excludes("--merge");
}

// --merge: the parts joined into the file one run would have written.
int merge_parts(const FfArgs& a) {
    const auto kind = radfmt::read_header(a.inputs.front()).kind;
    if (kind == radfmt::Kind::Links) {
        const auto links = rad::merge_link_parts(a.inputs, a.output);
        if (!a.options.quiet)
            std::fprintf(stderr, "rad-ff: merged %zu links part(s): %llu links\n", a.inputs.size(),
                         static_cast<unsigned long long>(links));
        return 0;
    }
    if (kind == radfmt::Kind::Sky) {
        const auto rows = rad::merge_sky_parts(a.inputs, a.output);
        if (!a.options.quiet)
            std::fprintf(stderr, "rad-ff: merged %zu sky part(s): %llu rows\n", a.inputs.size(),
                         static_cast<unsigned long long>(rows));
        return 0;
    }
    if (kind == radfmt::Kind::Luminaires) {
        const auto rows = rad::merge_luminaire_parts(a.inputs, a.output);
        if (!a.options.quiet)
            std::fprintf(stderr, "rad-ff: merged %zu luminaires part(s): %llu rows\n",
                         a.inputs.size(), static_cast<unsigned long long>(rows));
        return 0;
    }
    const auto merged =
        rad::merge_form_factor_parts(a.inputs, a.output, rad::tool::memory_limit(a.max_memory));
    if (!a.options.quiet)
        std::fprintf(stderr, "rad-ff: merged %zu part(s): %llu rows, %llu non-zeros\n",
                     a.inputs.size(), static_cast<unsigned long long>(merged.rows),
                     static_cast<unsigned long long>(merged.nonzeros));
    return 0;
}

// --method auto: analytic or hemisphere by the patch count, and why.
void choose_method(rad::FormFactorOptions& options, std::size_t patches, bool specular) {
    if (options.method != "auto") return;
    options.method = specular ? "hemisphere" : rad::automatic_form_factor_method(patches);
    const std::string why =
        specular ? "its rays go on through mirrors and glass, which the mesh has"
        : options.method == "analytic"
            ? "exact; above " + std::to_string(rad::kAutoAnalyticPatches) +
                  " patches hemisphere, whose rays grow as n, not analytic's pairs as n^2"
            : "rays, O(n); analytic's pairs grow as n^2: --method analytic insists";
    if (!options.quiet)
        std::fprintf(stderr, "rad-ff: --method auto: %s for %zu patches (%s)\n",
                     options.method.c_str(), patches, why.c_str());
}

// --error: the hemisphere's rows in batches, or a message saying why not.
void apply_error_option(FfArgs& a) {
    if (!a.error) return;
    auto& options = a.options;
    if (options.method != "hemisphere")
        throw rad::InputError(
            "--error estimates the sampling error of the hemisphere method's rays; the " +
            options.method +
            " method has none to estimate that way (analytic, hemicube and pairwise are "
            "quadratures): add --method hemisphere, or leave --error out");
    const int per_batch = options.rays / a.error_batches;
    if (options.rays % a.error_batches != 0 || per_batch < 8)
        throw rad::InputError("--error: --rays " + std::to_string(options.rays) +
                              " must be a multiple of --batches " +
                              std::to_string(a.error_batches) +
                              " with at least 8 rays a batch (e.g. --rays " +
                              std::to_string(std::max(8, per_batch + 1) * a.error_batches) + ")");
    options.error_batches = a.error_batches;
}

// Refuses a run whose estimated memory is past the limit, saying what to change.
void check_memory(const std::string& input, const radfmt::MeshData& mesh,
                  const rad::FormFactorOptions& options, std::uint64_t need, std::uint64_t limit,
                  const std::string& max_memory) {
    if (need <= limit) return;
    throw rad::InputError(
        input + ": " + options.method + " form factors for " + std::to_string(mesh.patches.size()) +
        " patches need up to " + rad::human_bytes(double(need)) + ", more than " +
        rad::tool::memory_limit_text(max_memory) +
        (options.method == "hemisphere" ? " (use fewer --rays or a coarser mesh)"
         : options.method == "hemicube" ? " (use a lower --resolution or a coarser mesh)"
                                        : " (use --method hemisphere or a coarser mesh)"));
}

// A whole matrix is encoded as its rows come (formfactors version 3: the spool holds what
// the file will); a part keeps the plain arrays.
std::optional<std::uint64_t> compact_encoding(const FfArgs& a) {
    if (!a.rows.empty()) return std::nullopt;
    radfmt::Header fields;
    for (const auto& [key, value] : rad::form_factor_header_fields(a.options))
        fields.set(key, value);
    return radfmt::formfactors_hit_denominator(fields);
}

// The form-factor file, or a part of one for --rows.
void write_rows(const FfArgs& a, const radfmt::MeshData& mesh, const radfmt::Header& mesh_header,
                radfmt::FormFactorSpool& ff, rad::RowRange range, const rad::FormFactorStats& stats,
                int argc, char** argv) {
    const auto& input = a.inputs.front();
    const radfmt::Parent parents[] = {{input, &mesh_header}};
    auto header = radfmt::derived_header(rad::tool_version("rad-ff"),
                                         radfmt::command_line(argc, argv), parents);
    for (const auto& [key, value] : rad::form_factor_header_fields(a.options))
        header.set(key, value);
    for (const auto& [key, value] : rad::specular_header_fields(mesh, a.options))
        header.set(key, value);
    header.set("mesh_geometry_hash", mesh.geometry_hash());
    header.set("rays_started_inside", std::to_string(stats.rays_started_inside));
    if (!a.rows.empty()) {
        // A part: the merge checks the parts against each other and writes the command
        // one run would have had.
        header.set("unsharded_command", rad::unsharded_command(argc, argv));
        radfmt::write_form_factor_part(a.output, header, ff, range.begin, range.end);
    } else {
        radfmt::write_form_factors(a.output, header, ff);
    }
}

// Warnings go out even with --quiet: a wrong-facing surface spoils every solve.
void warn_back_faces(const FfArgs& a, const radfmt::MeshData& mesh,
                     const radfmt::FormFactorSpool& ff, const rad::FormFactorStats& stats) {
    const auto& input = a.inputs.front();
    if (stats.rays_started_inside)
        std::fprintf(stderr,
                     "rad-ff: warning: %s: %llu ray(s) from %zu patch(es) met a back face "
                     "within their own patch's size: those patches are partly under or "
                     "inside other geometry (a contact not imprinted: rad-mesh imprints "
                     "unless --no-imprint; a lamp's back a hair below a ceiling), or beside a "
                     "surface facing away; that part of them sees nothing\n",
                     input.c_str(), static_cast<unsigned long long>(stats.rays_started_inside),
                     stats.patches_started_inside);
    // (A part sees its own rows only: the groups' warnings need them all.)
    if (!a.rows.empty()) return;
    const auto lines = rad::back_face_warnings(mesh, ff.back_fraction(), stats);
    const std::size_t shown =
        a.verbose ? lines.size() : std::min<std::size_t>(lines.size(), kMaxWarningLines);
    for (std::size_t k = 0; k < shown; ++k)
        std::fprintf(stderr, "rad-ff: warning: %s: %s\n", input.c_str(), lines[k].c_str());
    if (shown < lines.size())
        std::fprintf(stderr,
                     "rad-ff: warning: %s: %zu more group(s) face the wrong way or look at "
                     "backs, each over a smaller area than those above (rad-ff -v lists them "
                     "all; rad-mesh --orient fix turns what faces the wrong way)\n",
                     input.c_str(), lines.size() - shown);
}

void print_summary(const FfArgs& a, const radfmt::FormFactorSpool& ff,
                   const rad::FormFactorStats& stats, std::uint64_t limit, int threads) {
    if (a.options.quiet) return;
    if (ff.spilled())
        std::fprintf(stderr, "rad-ff: the rows beyond --max-memory (%s) waited on disk in %s\n",
                     rad::human_bytes(double(limit)).c_str(),
                     radfmt::FormFactorSpool::folder_for(a.output).c_str());
    std::fprintf(stderr,
                 "rad-ff: %llu patches, %llu non-zeros, %llu rays in %.3f s (%.3g rays/s "
                 "while tracing, %d threads), row sums mean %.5f max %.5f\n",
                 static_cast<unsigned long long>(ff.patch_count()),
                 static_cast<unsigned long long>(ff.nonzeros()),
                 static_cast<unsigned long long>(stats.rays_cast), stats.seconds,
                 stats.trace_seconds > 0 ? stats.rays_cast / stats.trace_seconds : 0.0, threads,
                 stats.mean_row_sum, stats.max_row_sum);
    const auto& errors = ff.row_error();
    if (errors.empty()) return;
    double sum = 0, max = 0;
    for (const float e : errors) sum += e, max = std::max(max, double(e));
    std::fprintf(stderr,
                 "rad-ff: rows' standard errors (%d batches): mean %.3g, max %.3g (rad-info "
                 "--csv lists each)\n",
                 a.error_batches, sum / double(errors.size()), max);
}

// The arguments that need each other, checked before the mesh is read.
void check_arguments(const FfArgs& a) {
    if (a.output_option->count() == 0 && !a.estimate_only)
        throw rad::InputError("--output is required (or --estimate, to measure only)");
    if (!a.estimate_only) rad::tool::check_outputs(a.inputs, {{"-o", a.output}});
}

// Lumens a group's direct light brings to the patches: sum of lux x area in m^2.
double lumens_received(const radfmt::MeshData& mesh, const radfmt::LuminaireData& lum,
                       std::size_t group, double metres_per_unit) {
    double total = 0;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        total += rad::lux(lum.of(i, group)) * mesh.patches[i].area;
    return total * metres_per_unit * metres_per_unit;
}

void print_direct_summary(const radfmt::MeshData& mesh, const rad::LuminaireSet& set,
                          const radfmt::LuminaireData& lum, const rad::DirectLightStats& stats) {
    double emitted = 0, received = 0;
    for (const auto& l : set.luminaires) emitted += set.flux(l);
    for (std::size_t g = 0; g < lum.groups.size(); ++g)
        received += lumens_received(mesh, lum, g, set.metres_per_unit);
    std::fprintf(stderr,
                 "rad-ff: %zu luminaire(s) from %zu photometric file(s) in %zu light group(s): "
                 "%.6g lm emitted (%.6g W at %g lm/W), %.6g lm reach the patches; %llu rays "
                 "in %.3f s\n",
                 set.luminaires.size(), set.photometries.size(), set.groups.size(), emitted,
                 emitted / rad::kRadianceEfficacy, rad::kRadianceEfficacy, received,
                 static_cast<unsigned long long>(stats.rays), stats.seconds);
}

// --luminaires: each luminaire's direct light per patch, into a .lum file.
int direct_light(FfArgs& a, int argc, char** argv) {
    if (a.merge || a.estimate_only)
        throw rad::InputError("--luminaires takes neither --merge (give the parts alone) nor "
                              "--estimate");
    if (a.inputs.size() != 1) throw rad::InputError("give one mesh with --luminaires");
    rad::ThreadLimit thread_limit(a.threads);
    const auto& input = a.inputs.front();
    radfmt::Header mesh_header;
    const auto mesh = radfmt::read_mesh(input, &mesh_header);
    if (mesh.patches.empty()) throw rad::InputError(input + ": mesh has no patches");
    rad::check_ray_precision(mesh.vertices, input);
    const auto sources = rad::read_luminaire_sources(a.luminaires);
    // Per patch and light group an RGB irradiance, held and written: checked before the
    // luminaires are built and the rays cast.
    const double need = double(mesh.patches.size()) * double(sources.group_count) * 24 * 2;
    if (const auto limit = rad::tool::memory_limit(a.max_memory); need > double(limit))
        throw rad::InputError(a.luminaires + ": " + std::to_string(sources.group_count) +
                              " light group(s) over " + std::to_string(mesh.patches.size()) +
                              " patches need about " + rad::human_bytes(need) + ", more than " +
                              rad::tool::memory_limit_text(a.max_memory) +
                              " (join luminaires in fewer groups: the layout's group column; "
                              "or a larger --max-memory)");
    const auto set = rad::build_luminaires(sources, rad::metres_per_unit(mesh_header));
    for (const auto& w : set.warnings) std::fprintf(stderr, "rad-ff: warning: %s\n", w.c_str());
    for (const auto& w :
         rad::luminaire_position_warnings(set, rad::bounds(mesh.vertices), a.luminaires))
        std::fprintf(stderr, "rad-ff: warning: %s\n", w.c_str());
    const rad::RayScene scene(mesh);
    // Their light passes thin panes and is seen in planar mirrors.
    const rad::SpecularSurfaces glass(mesh);
    const auto mirrors = rad::planar_mirrors(mesh, glass);
    for (const auto& w : rad::enclosed_luminaire_warnings(set, scene, a.luminaires))
        std::fprintf(stderr, "rad-ff: warning: %s\n", w.c_str());
    rad::DirectLightStats stats;
    const auto range =
        a.rows.empty() ? rad::RowRange{} : rad::parse_rows(a.rows, mesh.patches.size());
    radfmt::LuminaireData lum{sources.layout_name,
                              sources.layout_text,
                              sources.files,
                              set.groups,
                              mesh.patches.size(),
                              rad::patch_direct_light(mesh, set, scene, range.begin, range.end,
                                                      &stats, a.options.quiet, {&glass, &mirrors})};
    // The inputs: the mesh, the layout and every file it names, so Make and the chain see a
    // changed photometric file.
    std::vector<radfmt::Parent> parents{{input, &mesh_header}, {a.luminaires, nullptr}};
    const auto folder = std::filesystem::path(a.luminaires).parent_path();
    for (const auto& f : sources.files) parents.push_back({folder / f.first, nullptr});
    auto header = radfmt::derived_header(rad::tool_version("rad-ff"),
                                         radfmt::command_line(argc, argv), parents);
    header.set("mesh_geometry_hash", mesh.geometry_hash());
    header.set("metres_per_unit", std::to_string(set.metres_per_unit));
    header.set("luminaires", std::to_string(set.luminaires.size()));
    if (!a.rows.empty()) { // a part: rad-ff --merge joins the parts
        header.set("rows_begin", std::to_string(range.begin));
        header.set("rows_end",
                   std::to_string(std::min<std::uint64_t>(range.end, mesh.patches.size())));
        header.set("unsharded_command", rad::unsharded_command(argc, argv));
    }
    radfmt::write_luminaires(a.output, header, lum);
    if (!a.options.quiet) print_direct_summary(mesh, set, lum, stats);
    return 0;
}

// What rad-ff --sky says it did.
void print_sky_summary(const FfArgs& a, const rad::SkyViewOptions& options,
                       const std::vector<rad::Rgb>& view, const rad::SkyViewStats& stats) {
    const std::size_t count = options.patches.count();
    std::size_t seeing = 0;
    for (std::size_t i = 0; i < view.size() / count; ++i)
        seeing += std::any_of(view.begin() + long(i * count), view.begin() + long((i + 1) * count),
                              [](const rad::Rgb& c) { return rad::luminous(c) > 0; });
    std::fprintf(stderr,
                 "rad-ff: %s sky (%zu patches with the ground), north %g deg: %zu of %zu "
                 "patches see it, %.3g%% of %llu rays left the scene; %.3f s\n",
                 options.patches.spec().c_str(), count, a.north, seeing, view.size() / count,
                 100.0 * double(stats.escaped) / double(std::max<std::uint64_t>(1, stats.rays)),
                 static_cast<unsigned long long>(stats.rays), stats.seconds);
}

// The .sky (or a part of it: every patch, only `range`'s rows filled) from the rows computed.
void write_sky_view(const FfArgs& a, const radfmt::MeshData& mesh,
                    const radfmt::Header& mesh_header, const rad::SkyViewOptions& options,
                    const std::vector<rad::Rgb>& view, rad::RowRange range, int argc, char** argv) {
    const std::size_t count = options.patches.count();
    const std::uint64_t first = std::min<std::uint64_t>(range.begin, mesh.patches.size());
    radfmt::SkyData sky{options.patches.spec(), a.north, mesh.patches.size(), count,
                        std::vector<float>(mesh.patches.size() * count * 3, 0.0f)};
    for (std::size_t k = 0; k < view.size(); ++k)
        for (std::size_t c = 0; c < 3; ++c)
            sky.coefficients[(first * count + k) * 3 + c] = float(view[k][c]);
    const radfmt::Parent parents[] = {{a.inputs.front(), &mesh_header}};
    auto header = radfmt::derived_header(rad::tool_version("rad-ff"),
                                         radfmt::command_line(argc, argv), parents);
    header.set("mesh_geometry_hash", mesh.geometry_hash());
    header.set("rays", std::to_string(options.rays));
    header.set("seed", std::to_string(options.seed));
    if (mesh.has_specular()) header.set("specular_depth", std::to_string(options.specular_depth));
    if (!a.rows.empty()) {
        header.set("rows_begin", std::to_string(first));
        header.set("rows_end",
                   std::to_string(std::min<std::uint64_t>(range.end, mesh.patches.size())));
        header.set("unsharded_command", rad::unsharded_command(argc, argv));
    }
    radfmt::write_sky(a.output, header, sky);
}

// --sky: each patch's view of the sky patches and the ground, into a .sky file.
int sky_view(FfArgs& a, int argc, char** argv) {
    if (a.merge || a.estimate_only)
        throw rad::InputError("--sky takes neither --merge (give the parts alone) nor --estimate");
    if (a.inputs.size() != 1) throw rad::InputError("give one mesh with --sky");
    rad::SkyViewOptions options{rad::SkyPatches::parse(a.sky), rad::SkyFrame{a.north},
                                a.rays_option->count() ? a.options.rays : 1000, a.options.seed,
                                a.options.specular_depth};
    rad::ThreadLimit thread_limit(a.threads);
    const auto& input = a.inputs.front();
    radfmt::Header mesh_header;
    const auto mesh = radfmt::read_mesh(input, &mesh_header);
    if (mesh.patches.empty()) throw rad::InputError(input + ": mesh has no patches");
    rad::check_ray_precision(mesh.vertices, input);
    const double need = double(mesh.patches.size()) * double(options.patches.count()) * 12 * 2;
    if (const auto limit = rad::tool::memory_limit(a.max_memory); need > double(limit))
        throw rad::InputError(input + ": " + options.patches.spec() + " over " +
                              std::to_string(mesh.patches.size()) + " patches needs about " +
                              rad::human_bytes(need) + ", more than " +
                              rad::tool::memory_limit_text(a.max_memory) +
                              " (a coarser subdivision or mesh, or a larger --max-memory)");
    const auto range =
        a.rows.empty() ? rad::RowRange{} : rad::parse_rows(a.rows, mesh.patches.size());
    const rad::RayScene scene(mesh);
    const rad::SpecularSurfaces specular(mesh);
    rad::SkyViewStats stats;
    const auto view = rad::patch_sky_view(mesh, scene, specular, options, range.begin, range.end,
                                          &stats, a.options.quiet);
    write_sky_view(a, mesh, mesh_header, options, view, range, argc, argv);
    if (!a.options.quiet) print_sky_summary(a, options, view, stats);
    return 0;
}

int form_factors(FfArgs& a, int argc, char** argv) {
    check_arguments(a);
    if (a.error && (a.merge || !a.luminaires.empty() || !a.sky.empty()))
        throw rad::InputError("--error estimates the form factors' rows as they are cast: not "
                              "with --merge (parts keep their rows' errors), --luminaires or "
                              "--sky");
    if (a.merge) return merge_parts(a);
    if (!a.luminaires.empty() && !a.sky.empty())
        throw rad::InputError("--luminaires or --sky: one light source file per run");
    if (!a.luminaires.empty()) return direct_light(a, argc, argv);
    if (!a.sky.empty()) return sky_view(a, argc, argv);
    if (a.inputs.size() != 1)
        throw rad::InputError("give one mesh (several inputs are for --merge)");
    const auto& input = a.inputs.front();
    const std::uint64_t limit = rad::tool::memory_limit(a.max_memory);
    rad::ThreadLimit thread_limit(a.threads);
    radfmt::Header mesh_header;
    const auto mesh = radfmt::read_mesh(input, &mesh_header);
    if (mesh.patches.empty()) throw rad::InputError(input + ": mesh has no patches");
    auto& options = a.options;
    choose_method(options, mesh.patches.size(), mesh.has_specular());
    apply_error_option(a);
    rad::check_ray_precision(mesh.vertices, input);
    if (options.method == "hierarchical") {
        if (a.estimate_only)
            throw rad::InputError("--method hierarchical refines links from the whole tree: "
                                  "it has no --estimate");
        a.hierarchy.samples = options.samples > 0 ? options.samples : rad::kDefaultLinkSamples;
        a.hierarchy.seed = options.seed;
        if (!a.rows.empty()) set_link_shard(a.rows, mesh.patches.size(), a.hierarchy);
        write_hierarchical(input, mesh, mesh_header, a.hierarchy, a.output, argc, argv,
                           !a.rows.empty(), options.quiet);
        return 0;
    }
    options = rad::resolve_form_factor_options(options);
    const auto need = rad::estimate_form_factor_memory(mesh, options);
    check_memory(input, mesh, options, need, limit, a.max_memory);
    const auto range =
        a.rows.empty() ? rad::RowRange{} : rad::parse_rows(a.rows, mesh.patches.size());
    if (a.estimate_only) {
        say_estimate(mesh, options, range, true);
        return 0;
    }
    if (!options.quiet) say_estimate(mesh, options, range, false);
    // The rows are packed into the file's arrays as they are computed; what would not fit
    // within --max-memory waits on disk beside the output.
    rad::FormFactorStats stats;
    radfmt::FormFactorSpool ff(mesh.patches.size(), radfmt::FormFactorSpool::folder_for(a.output),
                               limit - need, compact_encoding(a));
    rad::compute_form_factor_rows(
        mesh, options,
        [&](std::size_t, rad::FormFactorEntries row, const rad::FormFactorRowFacts& facts) {
            ff.add_row(row, facts.back_fraction);
            if (facts.standard_error >= 0) ff.add_row_error(facts.standard_error);
        },
        &stats, range);
    write_rows(a, mesh, mesh_header, ff, range, stats, argc, argv);
    warn_back_faces(a, mesh, ff, stats);
    print_summary(a, ff, stats, limit, thread_limit.threads());
    return 0;
}
} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Compute the form factors F_ij between every pair of patches of a mesh (ray-cast\n"
        "visibility with Embree, rows in parallel) and write the sparse form-factor file."};
    FfArgs args;
    add_file_options(app, args);
    add_method_options(app, args);
    add_run_options(app, args);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::restart_with_huge_pages(argv);
    return rad::tool::run_tool("rad-ff", [&] { return form_factors(args, argc, argv); });
}
