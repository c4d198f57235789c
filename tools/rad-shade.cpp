// rad-shade: mesh + radiosity + view -> linear OpenEXR image (+ PNG preview, PLY mesh).
#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/auto_view.hpp"
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/daylight_glare.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/gathered.hpp"
#include "radiosity/huge_pages.hpp"
#include "radiosity/image_parts.hpp"
#include "radiosity/irradiance_cache.hpp"
#include "radiosity/irradiance_gradients.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/luminaire_image.hpp"
#include "radiosity/luminance_map.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/shade.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/specular_view.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <cstdio>
#include <iostream>

namespace {
// rad-shade --gather with no count: the rays rad-gather casts per point by default.
const int kDefaultGatherRays = rad::GatherOptions{}.rays;

// What the command line says.
struct ShadeArgs {
    std::vector<std::string> inputs;
    std::string rows;
    bool merge = false;
    std::string mesh_path, rad_path, output, view_text, view_file, smooth = "crease", png, ply;
    int width = 512, height = 512, aa = 2, threads = 0;
    double exposure = 0, crease = 30;
    bool flat = false, albedo = false, quiet = false;
    std::vector<std::string> mix;
    bool mix_only = false, layers = false, error_layer = false, no_cache = false;
    rad::IrradianceCacheOptions cache;
    std::string backfaces = "show", max_memory, direct_path;
    int gather = 0, shadow_rays = 32;
    // --gather's error bar and rounds: a pixel takes exactly its rays unless --accuracy.
    rad::GatherOptions sampling = [] {
        rad::GatherOptions o;
        o.accuracy = 0;
        return o;
    }();
    rad::tool::SkyChoice sky; // a daylight solution under one sky
    std::string falsecolor, luminance_table;
    double falsecolor_top = 0;
    int falsecolor_decades = 4;
};

// The inputs, the camera and the image's size.
void add_image_options(CLI::App& app, ShadeArgs& a) {
    app.add_option("MESH RADIOSITY", a.inputs,
                   "Patch mesh from rad-mesh, and radiosity from rad-solve (not needed with "
                   "--albedo); with --merge: the part files to join")
        ->required();
    app.add_option("-o,--output", a.output, "Output OpenEXR image")->required();
    app.add_option("--view", a.view_text,
                   "Radiance view options, e.g. \"-vp 0 1 3 -vd 0 0 -1 -vu 0 1 0 -vh 40 -vv 40\" "
                   "(neither --view nor --view-file: rad-shade chooses a camera that sees the "
                   "surfaces' fronts, standing inside an enclosed interior at eye height, else "
                   "from outside each side of the scene or inside it, and prints it)");
    app.add_option("--view-file", a.view_file,
                   "File with Radiance view options (e.g. scenes/cornell/cornell.vf)");
    app.add_option("-x,--width", a.width, "Image width in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    app.add_option("-y,--height", a.height, "Image height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    app.add_option("--aa", a.aa, "Supersampling: N x N samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    rad::tool::add_common_options(
        app, {.threads = &a.threads,
              .quiet = &a.quiet,
              .max_memory = &a.max_memory,
              .max_memory_refuses = "a render whose images are",
              .rows = &a.rows,
              .merge = &a.merge,
              .tool = "rad-shade",
              .rows_unit = "image rows",
              .rows_extra = ", from the top; each part an EXR of the image's size",
              .merge_result = "-o and the --png the parts were given (or this run's --png)"});
}

// How patches become colours, and the extra outputs.
void add_look_options(CLI::App& app, ShadeArgs& a) {
    app.add_flag("--flat", a.flat, "One colour per patch (same as --smooth flat)");
    app.add_option("--smooth", a.smooth,
                   "crease: area-weighted, not across material or group boundaries or sharp "
                   "edges (each surface keeps its own colour); average: vertex = mean of "
                   "adjacent patches (the paper's, which mixes colours where surfaces meet); "
                   "area: area-weighted; flat")
        ->capture_default_str()
        ->check(CLI::IsMember({"average", "area", "crease", "flat"}));
    app.add_option("--crease-angle", a.crease,
                   "crease: largest normal angle smoothed across (degrees)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 180));
    app.add_flag("--albedo", a.albedo,
                 "Show reflectance colours only, flat (the paper's Figure 1(a) and 4)");
    app.add_option("--png", a.png, "Also write an sRGB tone-mapped PNG preview");
    app.add_option("--ply", a.ply, "Also write the smoothed mesh with vertex colours as PLY");
    app.add_option(
           "--exposure", a.exposure,
           "Linear multiplier for PNG/PLY (default, or 0: from the solution, the same "
           "for every view: 0.85 over the luminance that 99% of the area of the "
           "surfaces that do not emit stays below, or of the emitters when only they are lit; "
           "--albedo: from the image)")
        ->check(rad::tool::finite_range(0, 1e30));
    app.add_option("--falsecolor", a.falsecolor,
                   "Also write the luminance (cd/m^2) as a false-colour PNG on a logarithmic "
                   "scale with a labelled legend, as designers read Radiance's falsecolor");
    app.add_option("--falsecolor-top", a.falsecolor_top,
                   "--falsecolor: the scale's top, cd/m^2 (default: the brightest pixel rounded "
                   "up to 1, 2, 2.5 or 5 x 10^k)")
        ->check(rad::tool::finite_range(0, 1e30));
    app.add_option("--falsecolor-decades", a.falsecolor_decades,
                   "--falsecolor: decades the scale spans below its top")
        ->capture_default_str();
    app.add_option("--luminance-table", a.luminance_table,
                   "Also write a CSV of the luminance of each surface (material) the view sees: "
                   "surface, pixels, share of the image, mean and largest cd/m^2");
    app.add_option("--backfaces", a.backfaces,
                   "Faces seen from behind (the side of a one-sided patch that gets no light): "
                   "show them as they are, or mark them in magenta (a face-orientation overlay)")
        ->capture_default_str()
        ->check(CLI::IsMember({"show", "mark"}));
}

// Light groups and the final gather.
void add_light_options(CLI::App& app, ShadeArgs& a) {
    app.add_option("--mix", a.mix,
                   "Weight a light group (rad-solve --light-groups): NAME=s, or NAME=r,g,b to "
                   "recolour it (repeatable; groups not named keep weight 1)");
    app.add_flag("--mix-only", a.mix_only, "Groups not named in --mix are off (weight 0)");
    rad::tool::add_sky_options(app, a.sky,
                               "A daylight solution (rad-solve --direct SKY) under this sky: its "
                               "sky patches' groups weighted by the sky's luminance");
    app.add_option("--direct", a.direct_path,
                   "The luminaires file (.lum) the solution was solved with, when it has moved "
                   "(default: the one rad-solve --direct recorded): their openings are drawn at "
                   "their luminance, and --gather adds their direct light exactly; with --sky, "
                   "the sky-view file (.sky) it was solved with, whose view of the sun's sky "
                   "patch is taken out so that the beam is drawn sharp");
    app.add_flag("--layers", a.layers,
                 "Also write one EXR layer per light group (<group>.R/G/B, each at weight 1, "
                 "for relighting in a compositor) next to the mixed image");
    app.add_option("--gather", a.gather,
                   "[N] Final gather: each sample is E + rho x the irradiance gathered at the "
                   "visible point with N indirect rays (--gather alone: " +
                       std::to_string(kDefaultGatherRays) +
                       "; direct light sampled on the emitters): sharp shadows, no blotches; "
                       "slower (0, or no --gather: off)")
        ->expected(0, 1)
        ->default_str(std::to_string(kDefaultGatherRays))
        ->check(CLI::Range(0, 1000000));
    app.add_option("--shadow-rays", a.shadow_rays,
                   "--gather: shadow rays per sample for the direct light, shared among the "
                   "lights (emitting patches, and patches lit so brightly that rays landing "
                   "on them would be fireflies) by what each contributes")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    rad::tool::add_accuracy_options(app, a.sampling);
    app.add_flag("--no-cache", a.no_cache,
                 "--gather: every sample casts all its indirect rays, instead of taking the "
                 "indirect light from an irradiance cache of records spread over the view "
                 "(docs/images.md); --error-layer and --accuracy imply it");
    app.add_option("--cache-rays", a.cache.rays,
                   "--gather: indirect rays of a cache record (about: a theta x phi grid)")
        ->capture_default_str()
        ->check(CLI::Range(16, 1000000));
    app.add_option("--cache-spacing", a.cache.spacing,
                   "--gather: a cache record every N pixels, across and down")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    app.add_option("--cache-accuracy", a.cache.accuracy,
                   "--gather: how far a record is reused (Ward's a: smaller is finer and slower)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0.01, 1));
    app.add_flag("--error-layer", a.error_layer,
                 "--gather: add an EXR layer 'error' holding each pixel's standard error (RGB, "
                 "the image's units): what the gather's sampling leaves uncertain there "
                 "(docs/uncertainty.md)");
}

// -o is an OpenEXR image and --png a PNG: a name that says the other format would hold what
// it does not say (an EXR named .png opens nowhere).
void check_output_names(const ShadeArgs& a) {
    const auto o = rad::tool::lower_extension(a.output);
    if (o == ".png" || o == ".jpg" || o == ".jpeg")
        throw rad::InputError("-o " + a.output +
                              ": -o writes the OpenEXR image (high dynamic range): name it .exr, "
                              "and give --png " +
                              a.output + " for the tone-mapped PNG");
    if (rad::tool::lower_extension(a.png) == ".exr")
        throw rad::InputError("--png " + a.png +
                              ": --png writes a tone-mapped PNG: name it .png (-o writes the "
                              "OpenEXR image)");
}

// Combinations that cannot work, refused before anything is read.
void check_combinations(const ShadeArgs& a) {
    if (a.error_layer && a.gather <= 0)
        throw rad::InputError("--error-layer holds the final gather's errors: give --gather");
    if (a.error_layer && !a.rows.empty())
        throw rad::InputError("--error-layer is written by a run of the whole image, not by a "
                              "--rows band");
    if (!a.rows.empty() && (!a.ply.empty() || a.layers))
        throw rad::InputError("--rows renders a band of the image: --ply and --layers are "
                              "written by a run of the whole image");
    if (!a.rows.empty() && a.view_text.empty() && a.view_file.empty())
        throw rad::InputError("--rows renders a band of one camera's image: give it with "
                              "--view or --view-file (rad-shade without them prints the view "
                              "it chooses)");
    if (a.albedo && (!a.mix.empty() || a.mix_only || a.layers))
        throw rad::InputError("--mix, --mix-only and --layers need a radiosity file, not "
                              "--albedo");
    const bool luminance = !a.falsecolor.empty() || !a.luminance_table.empty();
    if (luminance && a.albedo)
        throw rad::InputError("--falsecolor and --luminance-table show luminance: not with "
                              "--albedo");
    if (a.falsecolor_decades < 1 || a.falsecolor_decades > 9)
        throw rad::InputError("--falsecolor-decades " + std::to_string(a.falsecolor_decades) +
                              ": give 1 to 9 decades below the top");
    if (luminance && !a.rows.empty())
        throw rad::InputError("--falsecolor and --luminance-table are written by a run of the "
                              "whole image, not by a --rows band");
    if (!a.albedo && a.rad_path.empty())
        throw rad::InputError("give a radiosity file (or use --albedo)");
}

// What is shaded: the mesh, a value per patch (radiosity mixed from its light groups, or the
// reflectance for --albedo), the chain of commands that made them.
struct ShadeInputs {
    radfmt::MeshData mesh;
    radfmt::Header mesh_header, rad_header;
    radfmt::RadiosityData radiosity;
    std::vector<radfmt::Rgb> values;
    std::vector<std::string> chain;
    std::optional<rad::LuminaireSet> luminaires; // the solve's rad-solve --direct
    // E and rho as solved (rad-solve's overrides are in the file's header): for the gather,
    // the beam and the exposure; empty with --albedo.
    radfmt::MeshData solved;
    std::optional<rad::SharpBeam> beam; // --sky with the sun up: its beam, sharp
    std::vector<radfmt::Rgb> exposed;   // with a sharp beam: the values it spreads
};

// --sky: the daylight solution's sky groups mixed by the sky's patch luminances; with the
// sun up, its beam sharp (the spread beam taken out by the solve's .sky, the beam traced
// where the camera sees a surface).
std::vector<radfmt::Rgb> sky_values(const ShadeArgs& a, ShadeInputs& in) {
    if (!a.mix.empty() || a.mix_only || a.layers || a.gather > 0)
        throw rad::InputError("--sky mixes the sky's groups itself: not with --mix, --mix-only, "
                              "--layers or --gather");
    const auto solution = rad::daylight_solution(in.radiosity, in.rad_header, a.rad_path);
    const auto sky = rad::tool::sky_of(a.sky, "", solution.frame);
    if (!a.quiet) std::fprintf(stderr, "rad-shade: %s\n", sky.describe().c_str());
    auto values = rad::sky_radiosity(solution, sky);
    if (!rad::sun_patch(solution.patches, sky)) return values;
    const auto view =
        rad::solution_sky_view(in.rad_header, a.rad_path, a.direct_path, in.mesh, a.mesh_path);
    in.beam = rad::sharp_beam(solution, view, in.solved, sky, values);
    // The exposure is the one of the solution's own light, the beam in it as it spread it.
    in.exposed = std::move(values);
    return in.beam->radiosity;
}

ShadeInputs read_inputs(const ShadeArgs& a) {
    ShadeInputs in;
    in.mesh = radfmt::read_mesh(a.mesh_path, &in.mesh_header);
    in.chain = in.mesh_header.chain();
    if (a.albedo) {
        for (const auto& p : in.mesh.patches)
            in.values.push_back(in.mesh.materials[p.material].reflectance);
        return in;
    }
    in.radiosity = radfmt::read_radiosity(a.rad_path, &in.rad_header);
    in.solved = in.mesh;
    rad::apply_recorded_overrides(in.solved, in.rad_header);
    in.values = a.sky.sky.empty()
                    ? rad::mix_light_groups(in.radiosity, a.mix, a.mix_only, a.rad_path)
                    : sky_values(a, in);
    if (a.layers && in.radiosity.group_count() == 0)
        throw rad::InputError(a.rad_path + " has no light groups for --layers (solve with "
                                           "rad-solve --light-groups)");
    radfmt::require_same_geometry(a.rad_path, in.rad_header, in.values.size(), a.mesh_path, in.mesh,
                                  "run rad-ff and rad-solve on " + a.mesh_path + " again");
    in.chain = in.rad_header.chain();
    in.luminaires = rad::solution_luminaires(in.rad_header, a.rad_path, a.direct_path, in.mesh,
                                             a.mesh_path, in.mesh_header);
    return in;
}

// Checked before rendering: a huge -x/-y/--aa must not eat the machine first.
void check_memory(const ShadeArgs& a, std::size_t group_count) {
    const std::uint64_t limit = rad::tool::memory_limit(a.max_memory);
    const int images = 1 + (a.layers ? static_cast<int>(group_count) : 0);
    const auto need = rad::estimate_render_memory(a.width, a.height, a.aa, images);
    if (need <= limit) return;
    std::string message = "a " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                          " image at --aa " + std::to_string(a.aa);
    if (images > 1) message += " with " + std::to_string(images - 1) + " layers";
    message += " needs about " + rad::human_bytes(double(need)) + ", more than " +
               rad::tool::memory_limit_text(a.max_memory) + " (use a smaller -x/-y or --aa)";
    throw rad::InputError(message);
}

// The image: smoothed patch colours, or the final gather from the solution as solved.
rad::Image render_image(const ShadeArgs& a, const ShadeInputs& in, const rad::View& view,
                        const radfmt::MeshData& solved, rad::Smoothing mode,
                        const rad::CornerColours& corners, rad::RowBand band) {
    if (in.beam)
        return rad::render_with_beam(solved, corners, *in.beam, view, a.width, a.height, a.aa,
                                     a.quiet, band);
    if (a.gather <= 0) return rad::render(in.mesh, corners, view, a.width, a.height, a.aa);
    if (a.albedo || !a.mix.empty() || a.mix_only || a.layers)
        throw rad::InputError("--gather shades a solution as solved: not with --albedo, "
                              "--mix, --mix-only or --layers");
    rad::GatherOptions options;
    options.rays = a.gather;
    options.shadow_rays = a.shadow_rays;
    options.batches = a.sampling.batches;
    options.accuracy = a.sampling.accuracy;
    options.max_rays = a.sampling.max_rays;
    options.smoothing = mode;
    options.crease_deg = a.crease;
    const rad::Gatherer gatherer(solved, in.values, options);
    // The cache shares rays among samples: a per-sample error bar or accuracy needs each
    // sample's own.
    const bool cached = !a.no_cache && !a.error_layer && !(options.accuracy > 0);
    return rad::render_gathered(gatherer, view, a.width, a.height, a.aa, a.quiet,
                                in.luminaires ? &*in.luminaires : nullptr, band,
                                cached ? &a.cache : nullptr);
}

// The luminaires' openings at their luminance, dimmed and tinted by --mix as their groups.
void draw_openings(const ShadeArgs& a, const ShadeInputs& in, const rad::View& view,
                   rad::Image& image) {
    const auto& set = *in.luminaires;
    std::vector<radfmt::Rgb> weights;
    if (!a.mix.empty() || a.mix_only) {
        const auto all = rad::mix_weights(in.radiosity, a.mix, a.mix_only, a.rad_path);
        for (const auto& g : set.groups) {
            const auto it =
                std::find(in.radiosity.group_names.begin(), in.radiosity.group_names.end(), g);
            weights.push_back(it == in.radiosity.group_names.end()
                                  ? radfmt::Rgb{{1, 1, 1}}
                                  : all[std::size_t(it - in.radiosity.group_names.begin())]);
        }
    }
    const rad::RayScene scene(in.mesh);
    rad::draw_luminaires(image, set, scene, view, a.aa, weights);
}

// A solution with no light anywhere renders black: say so, and how to light it (#53).
void warn_black(const ShadeArgs& a, const ShadeInputs& in) {
    if (a.albedo || in.luminaires) return;
    for (const auto& b : in.values)
        if (b[0] > 0 || b[1] > 0 || b[2] > 0) return;
    std::fprintf(stderr,
                 "rad-shade: warning: %s is black: nothing in it emits light (give a material "
                 "light with rad-solve --emission MATERIAL=r,g,b, or luminaires with rad-ff "
                 "--luminaires and rad-solve --direct)%s\n",
                 a.rad_path.c_str(),
                 a.mix_only || !a.mix.empty() ? "; or --mix turned every light group off" : "");
}

// A warning when much of the image shows the backs of surfaces.
void warn_back_faces(const ShadeArgs& a, const rad::Image& image) {
    const double back_share = double(image.back_face_pixels) / (double(a.width) * a.height);
    if (back_share > 0.01)
        std::fprintf(stderr,
                     "rad-shade: warning: %.1f%% of the image shows the back of surfaces "
                     "(they get no light from this side: they probably face the wrong way%s; "
                     "see rad-mesh --orient fix, --flip, --two-sided)\n",
                     100 * back_share,
                     a.backfaces == "mark" ? ", marked in magenta"
                                           : ", --backfaces mark shows where");
}

// The EXR's attributes: where the image came from.
// A part (--rows) records the command one run would have had (see unsharded_command).
std::map<std::string, std::string> exr_attributes(const ShadeArgs& a, const ShadeInputs& in,
                                                  int argc, char** argv) {
    std::map<std::string, std::string> attributes;
    std::string provenance;
    for (std::size_t i = 0; i < in.chain.size(); ++i)
        provenance += std::to_string(i + 1) + ". " + in.chain[i] + "\n";
    provenance +=
        std::to_string(in.chain.size() + 1) + ". " +
        (a.rows.empty() ? radfmt::command_line(argc, argv) : rad::unsharded_command(argc, argv)) +
        "\n";
    attributes["radiosity:provenance"] = provenance;
    attributes["radiosity:tool"] = rad::tool_version("rad-shade");
    attributes["radiosity:mesh"] = a.mesh_path + " " + in.mesh_header.file_hash;
    if (!a.albedo) attributes["radiosity:radiosity"] = a.rad_path + " " + in.rad_header.file_hash;
    attributes["radiosity:units"] = a.albedo ? "reflectance" : "radiosity W/m^2 (linear)";
    if (!a.mix.empty() || a.mix_only) {
        std::string text;
        for (const auto& m : a.mix) text += (text.empty() ? "" : " ") + m;
        attributes["radiosity:mix"] = (a.mix_only ? "only " : "") + text;
    }
    return attributes;
}

// One image per light group for --layers, each at weight 1.
std::vector<rad::Image> render_layers(const ShadeArgs& a, const ShadeInputs& in,
                                      const rad::View& view, rad::Smoothing mode) {
    std::vector<rad::Image> images;
    if (!a.layers) return images;
    images.reserve(in.radiosity.group_count());
    for (std::size_t g = 0; g < in.radiosity.group_count(); ++g) {
        std::vector<radfmt::Rgb> group_values(in.radiosity.radiosity.size());
        for (std::size_t i = 0; i < group_values.size(); ++i)
            group_values[i] = in.radiosity.of_group(i, g);
        images.push_back(rad::render(in.mesh,
                                     rad::corner_colours(in.mesh, group_values, mode, a.crease),
                                     view, a.width, a.height, a.aa));
    }
    return images;
}

// No camera given: one that sees the scene's surfaces from their front, said on stderr so
// that it can be given again (and changed).
rad::View chosen_view(const ShadeArgs& a, const radfmt::MeshData& mesh) {
    const rad::RayScene scene(mesh);
    const auto chosen = rad::choose_view(mesh, scene, double(a.width) / a.height);
    std::fprintf(stderr,
                 "rad-shade: no camera given: chose --view \"%s\" (%s; %.0f%% of its rays "
                 "see the front of a surface)\n",
                 chosen.text.c_str(), chosen.where.c_str(),
                 100 * std::max(0.0, chosen.front_share));
    return chosen.view;
}

// The exposure one run uses; 0 for a part whose exposure comes from the whole image.
double run_exposure(const ShadeArgs& a, const ShadeInputs& in, const radfmt::MeshData& solved,
                    const rad::Image& image) {
    double scale = a.exposure;
    if (!(scale > 0) && !a.albedo)
        scale = rad::solution_exposure(solved, in.exposed.empty() ? in.values : in.exposed);
    if (!(scale > 0) && a.rows.empty()) scale = rad::auto_exposure(image);
    return scale;
}

void say_written(const ShadeArgs& a, double scale) {
    if (a.quiet) return;
    std::fprintf(stderr, "rad-shade: wrote %s (%dx%d, %s%s), exposure %.4g\n", a.output.c_str(),
                 a.width, a.height,
                 a.albedo ? "albedo"
                 : a.flat ? "flat"
                          : a.smooth.c_str(),
                 a.png.empty() ? "" : ", png", scale);
}

// --falsecolor's picture and --luminance-table's rows.
void write_luminance(const ShadeArgs& a, const rad::Image& image,
                     const std::vector<rad::SurfaceLuminance>& surfaces) {
    if (!a.falsecolor.empty()) {
        const auto scale = rad::luminance_scale(image, a.falsecolor_top, a.falsecolor_decades);
        const auto png = rad::luminance_png(image, scale);
        rad::tool::write_output(
            a.falsecolor, [&](std::FILE* out) { std::fwrite(png.data(), 1, png.size(), out); });
        if (!a.quiet)
            std::fprintf(stderr, "rad-shade: --falsecolor %s: %g to %g cd/m^2, logarithmic\n",
                         a.falsecolor.c_str(), scale.bottom(), scale.top);
    }
    if (a.luminance_table.empty()) return;
    const double pixels = double(image.width) * image.height;
    rad::tool::write_output(a.luminance_table, [&](std::FILE* out) {
        std::fprintf(out, "surface,pixels,share,mean_cd_m2,max_cd_m2\n");
        for (const auto& s : surfaces)
            std::fprintf(out, "%s,%ld,%.6g,%.6g,%.6g\n", rad::csv_field(s.name).c_str(), s.pixels,
                         double(s.pixels) / pixels, s.mean, s.max);
    });
}

// --merge: the bands into the image (and PNG) one run writes.
int merge_parts(ShadeArgs& a) {
    check_output_names(a);
    if (!a.rows.empty()) throw rad::InputError("--merge joins parts: not with --rows");
    if (!a.falsecolor.empty() || !a.luminance_table.empty())
        throw rad::InputError("--falsecolor and --luminance-table are written by a run of the "
                              "whole image (they need what each pixel sees), not by --merge");
    auto merged = rad::merge_image_parts(a.inputs, a.output);
    // A merge writes only what its own command line names: the PNG path the parts recorded
    // (their run's --png) is a reminder, never a place to write.
    if (a.png.empty() && !merged.info.png.empty())
        std::fprintf(stderr,
                     "rad-shade: note: the parts were rendered with --png %s: give --png FILE "
                     "to the merge to write the PNG\n",
                     merged.info.png.c_str());
    merged.info.png = a.png;
    rad::tool::check_outputs(a.inputs, {{"-o", a.output}, {"--png", merged.info.png}});
    radfmt::OutputBatch outputs;
    auto& image = merged.image;
    if (image.covered_pixels == 0)
        throw rad::InputError("the view sees no geometry in any part (camera outside looking "
                              "away, or inside an object facing nothing)");
    const double scale =
        merged.info.exposure > 0 ? merged.info.exposure : rad::auto_exposure(image);
    if (merged.info.mark_backs) rad::mark_back_faces(image, {1 / scale, 0, 1 / scale});
    a.width = image.width;
    a.height = image.height;
    a.backfaces = merged.info.mark_backs ? "mark" : "show";
    warn_back_faces(a, image);
    rad::write_exr(a.output, image, merged.info.attributes);
    if (!merged.info.png.empty()) rad::write_png(merged.info.png, image, scale);
    outputs.commit();
    if (!a.quiet)
        std::fprintf(stderr, "rad-shade: merged %zu part(s) into %s%s%s (%dx%d), exposure %.4g\n",
                     a.inputs.size(), a.output.c_str(), merged.info.png.empty() ? "" : " and ",
                     merged.info.png.c_str(), image.width, image.height, scale);
    return 0;
}

// --rows: a band of the image into a part file.
void write_part(const ShadeArgs& a, rad::Image& image, rad::RowBand band,
                std::map<std::string, std::string> attributes, double scale) {
    rad::keep_rows(image, band);
    rad::ImagePartInfo info;
    info.band = band;
    info.attributes = std::move(attributes);
    info.exposure = scale;
    info.mark_backs = a.backfaces == "mark";
    info.png = a.png;
    rad::write_image_part(a.output, image, info);
    if (!a.quiet)
        std::fprintf(stderr, "rad-shade: wrote rows %d to %d of %d into the part %s\n", band.begin,
                     band.end - 1, a.height, a.output.c_str());
}

int shade(ShadeArgs& a, int argc, char** argv) {
    if (a.merge) return merge_parts(a);
    if (a.inputs.size() > 2)
        throw rad::InputError("give MESH and RADIOSITY (" + std::to_string(a.inputs.size()) +
                              " files given; several are for --merge)");
    a.mesh_path = a.inputs[0];
    if (a.inputs.size() > 1) a.rad_path = a.inputs[1];
    rad::tool::check_outputs({a.mesh_path, a.rad_path}, {{"-o", a.output},
                                                         {"--png", a.png},
                                                         {"--ply", a.ply},
                                                         {"--falsecolor", a.falsecolor},
                                                         {"--luminance-table", a.luminance_table}});
    // The image, its preview and the PLY land together or not at all.
    radfmt::OutputBatch outputs;
    rad::ThreadLimit thread_limit(a.threads);
    check_output_names(a);
    check_combinations(a);
    rad::View view = a.view_file.empty() ? rad::View{} : rad::read_view_file(a.view_file);
    if (!a.view_text.empty()) view = rad::parse_view(a.view_text, rad::FileLoc{"--view"}, view);
    const auto in = read_inputs(a);
    if (a.view_text.empty() && a.view_file.empty()) view = chosen_view(a, in.mesh);
    // The camera's rays are traced (--gather, the luminaires' openings): one check for every
    // position a tool is given.
    if (const auto why = rad::out_of_reach(view.position, rad::bounds(in.mesh.vertices));
        !why.empty())
        throw rad::InputError("the camera (-vp): " + why);
    if (a.albedo) a.flat = true;
    check_memory(a, in.radiosity.group_count());
    const auto mode = a.flat ? rad::Smoothing::Flat : rad::parse_smoothing(a.smooth);
    const auto corners = rad::corner_colours(in.mesh, in.values, mode, a.crease);
    const auto& solved = in.solved;
    warn_black(a, in);
    rad::RowBand band;
    if (!a.rows.empty()) {
        const auto range = rad::parse_rows(a.rows, std::uint64_t(a.height), "the image's rows");
        band = {int(range.begin), int(range.end)};
    }
    rad::Image image = render_image(a, in, view, solved, mode, corners, band);
    // Per surface before the luminaires' openings are drawn over what they hide.
    std::vector<rad::SurfaceLuminance> surfaces;
    if (!a.luminance_table.empty())
        surfaces = rad::surface_luminances(image, in.mesh, rad::RayScene(in.mesh), view);
    if (in.luminaires) draw_openings(a, in, view, image);
    if (!a.rows.empty()) { // a band: the merge checks coverage, exposes and marks the whole
        write_part(a, image, band, exr_attributes(a, in, argc, argv),
                   run_exposure(a, in, solved, image));
        outputs.commit();
        return 0;
    }
    if (image.covered_pixels == 0)
        throw rad::InputError("the view sees no geometry of " + a.mesh_path +
                              " (camera outside looking away, or inside an object facing "
                              "nothing)");
    // Exposure from the solution (every view of it alike; lamps in view do not set it), or
    // for albedo from the image; then the overlay in full magenta at that exposure.
    const double scale = run_exposure(a, in, solved, image);
    if (a.backfaces == "mark") rad::mark_back_faces(image, {1 / scale, 0, 1 / scale});
    warn_back_faces(a, image);
    if (image.cache_records > 0 && !a.quiet)
        std::fprintf(stderr,
                     "rad-shade: irradiance cache: %zu records of %d rays; %ld of the samples "
                     "no record covered shared a gather of their own, a pixel's on a patch\n",
                     image.cache_records, rad::hemisphere_grid(a.cache.rays).cells(),
                     image.uncached_samples);

    const auto group_images = render_layers(a, in, view, mode);
    std::vector<rad::ImageLayer> exr_layers;
    for (std::size_t g = 0; g < group_images.size(); ++g)
        exr_layers.push_back({in.radiosity.group_names[g], &group_images[g]});
    rad::Image error;
    if (a.error_layer) {
        if (image.error.empty()) throw rad::InternalError("the gathered image has no errors");
        error.width = image.width, error.height = image.height, error.rgb = image.error;
        exr_layers.push_back({"error", &error});
    }
    rad::write_exr(a.output, image, exr_attributes(a, in, argc, argv), exr_layers);
    if (!a.png.empty()) rad::write_png(a.png, image, scale);
    if (!a.ply.empty()) rad::write_ply(a.ply, in.mesh, corners, scale);
    write_luminance(a, image, surfaces);
    outputs.commit();
    say_written(a, scale);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Render per-patch radiosity from a camera (Radiance view options) to a linear\n"
                 "float OpenEXR image, with optional sRGB PNG preview and vertex-coloured PLY."};
    ShadeArgs args;
    add_image_options(app, args);
    add_look_options(app, args);
    add_light_options(app, args);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::restart_with_huge_pages(argv);
    return rad::tool::run_tool("rad-shade", [&] { return shade(args, argc, argv); });
}
