// rad-bake: mesh + radiosity -> binary glTF with the light baked in (vertex colours or a
// lightmap atlas), plus the atlas as linear EXR and sRGB PNG.
#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/bake.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/daylight_glare.hpp"
#include "radiosity/error.hpp"
#include "radiosity/huge_pages.hpp"
#include "radiosity/image_io.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/version.hpp"
#include "radiosity/view.hpp"
#include "tool.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>

namespace {

// A daylight page's components: layers of one texture array the fragment shader mixes; as
// many as bring a year of clear skies within 0.5% rms of the full solution, at most 64.
constexpr int kDaylightComponents = 64;
constexpr double kDaylightError = 0.005;

// What the glb says of where it came from (asset.extras.radiosity).
nlohmann::json provenance_json(const radfmt::Header& mesh_header, const std::string& mesh_path,
                               const radfmt::Header& rad_header, const std::string& rad_path,
                               const std::string& command, const rad::BakeOptions& options,
                               const rad::BakeResult& result) {
    nlohmann::json chain = rad_header.chain();
    chain.push_back(command);
    nlohmann::json extras = {
        {"tool", rad::tool_version("rad-bake")},
        {"provenance", chain},
        {"mesh", {{"path", mesh_path}, {"hash", mesh_header.file_hash}}},
        {"radiosity", {{"path", rad_path}, {"hash", rad_header.file_hash}}},
        {"exposure", options.exposure},
        {"values", "radiosity in W/m^2 times exposure, linear (sRGB in PNG textures), clamped "
                   "to 1; divide by exposure for W/m^2"}};
    if (options.lightmap_size > 0)
        extras["lightmap"] = {{"size", result.layout.size},
                              {"texels_per_metre", result.layout.texels_per_metre},
                              {"padding", result.layout.padding},
                              {"charts", result.charts},
                              {"texcoord", 1}};
    return extras;
}

// The page's settings: rad-shade's camera and the exposure.
std::string page_config(const rad::View& view, double exposure) {
    const nlohmann::json config = {{"view",
                                    {{"position", view.position},
                                     {"direction", view.direction},
                                     {"up", view.up},
                                     {"horizontal_deg", view.horizontal_deg},
                                     {"vertical_deg", view.vertical_deg}}},
                                   {"exposure", exposure}};
    return config.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

rad::Image lightmap_image(const rad::Lightmap& map) {
    rad::Image image;
    image.width = image.height = map.size;
    image.rgb = map.rgb;
    return image;
}

struct Arguments {
    std::string mesh_path, rad_path, output, smooth = "crease", exr, png, html, view_text,
                                             view_file, engine;
    double crease = 30, exposure = 0, density = 0, chart_angle = 20;
    int lightmap = 0, padding = 2, threads = 0;
    std::string max_memory, location, epw;
    bool quiet = false, mix_only = false;
    std::vector<std::string> mix;
    double ground = 0.2;
};

void add_options(CLI::App& app, Arguments& a) {
    app.add_option("MESH", a.mesh_path, "Patch mesh from rad-mesh")->required();
    app.add_option("RADIOSITY", a.rad_path, "Radiosity from rad-solve")->required();
    app.add_option("-o,--output", a.output, "Output binary glTF (.glb)")->required();
    app.add_option("--smooth", a.smooth, "Smoothing, as rad-shade's --smooth")
        ->capture_default_str()
        ->check(CLI::IsMember({"average", "area", "crease", "flat"}));
    app.add_option("--crease-angle", a.crease, "crease: largest normal angle smoothed across")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 180));
    app.add_option("--exposure", a.exposure,
                   "Linear multiplier from W/m^2 to display values (default, or 0: rad-shade's "
                   "exposure from the solution, so the glb looks like rad-shade's image)")
        ->check(rad::tool::finite_range(0, 1e30));
    app.add_option("--mix", a.mix, "Weight a light group, as rad-shade --mix (repeatable)");
    app.add_flag("--mix-only", a.mix_only, "Groups not named in --mix are off");
    app.add_option("--lightmap", a.lightmap,
                   "Bake a SIZE x SIZE lightmap atlas instead of vertex colours (e.g. 1024)")
        ->check(CLI::Range(8, 16384));
    app.add_option("--texels-per-metre", a.density,
                   "--lightmap: texel density (default: the highest at which the charts fit)")
        ->check(rad::tool::finite_range(0, 1e9));
    app.add_option("--padding", a.padding,
                   "--lightmap: texels around each chart, filled from its edge so bilinear "
                   "filtering never reads a neighbour")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    app.add_option("--chart-angle", a.chart_angle,
                   "--lightmap: largest angle between normals within one chart (degrees)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 60));
    app.add_option("--exr", a.exr,
                   "--lightmap: also write the atlas as linear float OpenEXR (radiosity, W/m^2; "
                   "one layer per light group)");
    app.add_option("--png", a.png, "--lightmap: also write the atlas as sRGB PNG (as in the glb)");
    app.add_option("--html", a.html,
                   "Also write a self-contained viewer page (three.js): the glb from the camera "
                   "of --view/--view-file at the same exposure, orbit controls, an exposure "
                   "slider and with light groups one slider per group (needs --lightmap)");
    app.add_option("--engine", a.engine,
                   "--lightmap: also write a glb for engines: the scene's own materials (base "
                   "colour = reflectance, emissive), TEXCOORD_1, and an irradiance atlas (what "
                   "falls on the surface, x exposure, sRGB) for the engine's lightmap slot, "
                   "named in asset.extras.radiosity.lightmap_texture");
    app.add_option("--location", a.location,
                   "--html of a daylight solution (rad-solve --direct SKY): LAT,LON,TZ, where the "
                   "page's date and time sliders put the sun; the page relights by clear sky "
                   "(CIE 12 with the IES daylight availability) from a basis of the solution "
                   "(needs --lightmap)");
    app.add_option("--epw", a.epw,
                   "--html of a daylight solution: also the hours of this weather file on the "
                   "page (each hour's Perez sky from its radiation, the sun at mid-hour, as "
                   "rad-gather --annual takes them); its place unless --location gives one");
    app.add_option("--ground", a.ground, "--location: the ground's reflectance below the horizon")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 1));
    app.add_option("--view", a.view_text, "--html: the camera, as rad-shade's --view");
    app.add_option("--view-file", a.view_file, "--html: the camera, as rad-shade's --view-file");
    rad::tool::add_common_options(
        app, {.threads = &a.threads,
              .quiet = &a.quiet,
              .max_memory = &a.max_memory,
              .max_memory_refuses = "a --lightmap atlas (times its light groups)"});
}

// The page's camera; throws InputError for options that do not go together.
rad::View checked_view(const Arguments& a) {
    if (a.lightmap == 0 && (!a.exr.empty() || !a.png.empty() || !a.engine.empty() || a.density > 0))
        throw rad::InputError("--exr, --png, --engine and --texels-per-metre need --lightmap SIZE");
    if (!a.html.empty() && a.view_text.empty() && a.view_file.empty())
        throw rad::InputError("--html needs a camera: give --view or --view-file");
    if (a.html.empty() && !(a.view_text.empty() && a.view_file.empty()))
        throw rad::InputError("--view and --view-file are for the --html page");
    rad::View view = a.view_file.empty() ? rad::View{} : rad::read_view_file(a.view_file);
    if (!a.view_text.empty()) view = rad::parse_view(a.view_text, rad::FileLoc{"--view"}, view);
    return view;
}

// Each light group's radiosity at weight 1, named.
std::vector<std::pair<std::string, std::vector<radfmt::Rgb>>>
group_radiosity(const radfmt::RadiosityData& radiosity) {
    std::vector<std::pair<std::string, std::vector<radfmt::Rgb>>> groups;
    for (std::size_t g = 0; g < radiosity.group_count(); ++g) {
        std::vector<radfmt::Rgb> group(radiosity.radiosity.size());
        for (std::size_t i = 0; i < group.size(); ++i) group[i] = radiosity.of_group(i, g);
        groups.emplace_back(radiosity.group_names[g], std::move(group));
    }
    return groups;
}

rad::BakeOptions bake_options(const Arguments& a, double solution_exposure) {
    rad::BakeOptions options;
    options.smoothing = rad::parse_smoothing(a.smooth);
    options.crease_deg = a.crease;
    options.exposure = a.exposure > 0 ? a.exposure : solution_exposure;
    if (!(options.exposure > 0)) options.exposure = 1; // nothing lit: show values as they are
    options.lightmap_size = a.lightmap;
    options.texels_per_metre = a.density;
    options.padding = a.padding;
    options.chart_angle_deg = a.chart_angle;
    return options;
}

// A lightmap whose atlas, times its light groups, would not fit in --max-memory is refused
// before baking (it failed after a minute at 16384 with 4 groups).
void check_lightmap_memory(const Arguments& a, std::size_t groups) {
    if (a.lightmap == 0) return;
    const auto need =
        rad::estimate_lightmap_memory(a.lightmap, groups, !a.engine.empty(), !a.exr.empty());
    const auto limit = rad::tool::memory_limit(a.max_memory);
    if (need <= limit) return;
    throw rad::InputError("--lightmap " + std::to_string(a.lightmap) + " with " +
                          std::to_string(groups) + " light group(s) needs about " +
                          rad::human_bytes(double(need)) + ", more than " +
                          rad::tool::memory_limit_text(a.max_memory) +
                          " (use a smaller --lightmap, or a larger --max-memory)");
}

// The atlas files beside the glb: linear EXR (a layer per group) and the sRGB PNG.
void write_atlas_files(const Arguments& a, const rad::BakeResult& result,
                       const std::vector<std::string>& group_names, double exposure) {
    if (!a.exr.empty()) {
        std::vector<rad::Image> group_images;
        std::vector<rad::ImageLayer> layers;
        for (const auto& map : result.group_lightmaps) group_images.push_back(lightmap_image(map));
        for (std::size_t g = 0; g < group_images.size(); ++g)
            layers.push_back({group_names[g], &group_images[g]});
        const auto irradiance = lightmap_image(result.irradiance);
        if (!a.engine.empty()) layers.push_back({"irradiance", &irradiance});
        rad::write_exr(a.exr, lightmap_image(result.lightmap),
                       {{"radiosity:tool", rad::tool_version("rad-bake")},
                        {"radiosity:units", "radiosity W/m^2 (linear); layer irradiance (with "
                                            "--engine): W/m^2 falling on the surface"},
                        {"radiosity:glb", a.output}},
                       layers);
    }
    if (!a.png.empty())
        rad::write_png_rgb8(a.png, result.layout.size, result.layout.size,
                            rad::lightmap_pixels(result.lightmap, exposure));
}

void print_summary(const Arguments& a, const radfmt::MeshData& mesh, const rad::BakeResult& result,
                   double exposure) {
    if (a.lightmap > 0)
        std::fprintf(stderr,
                     "rad-bake: wrote %s (%zu patches, %zu charts in a %dx%d lightmap at %.4g "
                     "texels/m%s), exposure %.4g\n",
                     a.output.c_str(), mesh.patches.size(), result.charts, a.lightmap, a.lightmap,
                     result.layout.texels_per_metre,
                     result.group_lightmaps.empty() ? "" : ", one lightmap per light group",
                     exposure);
    else
        std::fprintf(stderr, "rad-bake: wrote %s (%zu patches, vertex colours), exposure %.4g\n",
                     a.output.c_str(), mesh.patches.size(), exposure);
}

// The glb for engines: the scene's materials, and the irradiance atlas for their lightmap slot.
void write_engine_glb(const std::string& path, const rad::BakeResult& result, double exposure) {
    rad::BakeScene engine = result.scene;
    engine.engine_materials = true;
    engine.exposure = exposure;
    engine.lightmap_png = result.irradiance_png;
    engine.group_lightmaps_png.clear();
    auto extras = nlohmann::json::parse(engine.extras_json);
    extras["lightmap"]["content"] =
        "irradiance in W/m^2 times exposure (sRGB): an engine's albedo times it, plus the "
        "emissive, gives the baked radiosity";
    engine.extras_json = extras.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    const auto bytes = rad::baked_glb(engine);
    rad::write_file(path, bytes.data(), bytes.size());
}

// A daylight solution's page: the glb shows a clear equinox noon; the page relights by date
// and time from a basis of the solution (its components as signed lightmaps).
struct DaylightPage {
    rad::DaylightSolution solution;
    rad::Location where;
    rad::DaylightBasis basis;             // the sky and the ground, without the sun
    std::vector<std::size_t> sun_patches; // the sky patches the sun passes through
    std::vector<radfmt::Rgb> noon;        // the patches' radiosity at the glb's default sky
    std::optional<rad::Weather> weather;  // --epw
    rad::HourlySkies hours;               // its hours' skies
    radfmt::SkyData view;                 // the solve's .sky: the beam the sun layers spread
};

// The days the page offers besides a weather file's hours, in its menu's order.
constexpr rad::Sky::Day kPageDays[] = {rad::Sky::Day::clear, rad::Sky::Day::partly_cloudy,
                                       rad::Sky::Day::overcast};

// The skies the basis is made to reproduce: a year of each day (every fifth day), and the
// weather file's lit hours; the sky patches the sun is in over them, each once, ascending.
rad::YearOfSkies page_skies(const DaylightPage& page, double ground) {
    rad::YearOfSkies all;
    std::vector<bool> sun_in(page.solution.patches.count(), false);
    for (const auto day : kPageDays) {
        auto year =
            rad::day_year(page.solution.patches, page.solution.frame, page.where, ground, day);
        for (auto& sky : year.skies) all.skies.push_back(std::move(sky));
        for (const auto p : year.sun_patches) sun_in[p] = true;
    }
    const auto& h = page.hours;
    for (std::size_t t = 0; page.weather && t < page.weather->hours.size(); ++t) {
        const auto first = h.direct.begin() + std::ptrdiff_t(t * h.count);
        if (std::all_of(first, first + std::ptrdiff_t(h.count), [](float v) { return v == 0; }))
            continue;
        all.skies.emplace_back(first, first + std::ptrdiff_t(h.count));
        if (h.sun_patch[t] >= 0) sun_in[std::size_t(h.sun_patch[t])] = true;
    }
    for (std::size_t p = 0; p < sun_in.size(); ++p)
        if (sun_in[p]) all.sun_patches.push_back(p);
    return all;
}

std::optional<DaylightPage> daylight_page(const Arguments& a, const radfmt::MeshData& mesh,
                                          const radfmt::RadiosityData& radiosity,
                                          const radfmt::Header& rad_header) {
    if (!rad::is_daylight_solution(rad_header)) {
        if (!a.location.empty())
            throw rad::InputError("--location is for the page of a daylight solution (rad-solve "
                                  "--direct SKY); " +
                                  a.rad_path + " is none");
        return std::nullopt;
    }
    if (a.html.empty() || a.lightmap == 0 || (a.location.empty() && a.epw.empty()))
        throw rad::InputError(
            a.rad_path + " is a daylight solution (" + std::to_string(radiosity.group_count()) +
            " light groups, one per sky patch): bake its page with --html, "
            "--lightmap SIZE and --location LAT,LON,TZ or --epw FILE (it relights by date and "
            "time), or one sky with rad-shade --sky");
    if (!a.mix.empty() || a.mix_only) throw rad::InputError("--mix is not for a daylight page");
    DaylightPage page{
        rad::daylight_solution(radiosity, rad_header, a.rad_path), {}, {}, {}, {}, {}, {}, {}};
    page.view = rad::solution_sky_view(rad_header, a.rad_path, "", mesh, a.mesh_path);
    if (!a.epw.empty()) {
        page.weather = rad::read_epw(a.epw);
        page.hours =
            rad::hourly_skies(*page.weather, page.solution.patches, page.solution.frame, a.ground);
    }
    page.where = a.location.empty() ? page.weather->location : rad::parse_location(a.location);
    std::vector<double> areas;
    for (const auto& p : mesh.patches) areas.push_back(p.area);
    const auto skies = page_skies(page, a.ground);
    page.basis =
        rad::daylight_basis(page.solution, areas, skies.skies, kDaylightComponents, kDaylightError);
    page.sun_patches = skies.sun_patches;
    const auto sun = rad::solar_position(page.where, {2025, 3, 21, 12});
    page.noon =
        rad::sky_radiosity(page.solution, rad::Sky::clear(sun, page.solution.frame, a.ground));
    return page;
}

// A weather file's lit hours for the page, each as the page weighs them: the components'
// weights of its sky (the patches' luminances without the beam), the sun's patch and the
// beam's luminance in it, and the sky's mean luminance (for what the windows show).
nlohmann::json weather_extras(const DaylightPage& page) {
    const auto& h = page.hours;
    const std::size_t count = h.count;
    nlohmann::json hours = nlohmann::json::array(), weights = nlohmann::json::array(),
                   sun_patch = nlohmann::json::array(), beam = nlohmann::json::array(),
                   sky = nlohmann::json::array(), sun = nlohmann::json::array();
    const auto& patches = page.solution.patches;
    for (std::size_t t = 0; t < page.weather->hours.size(); ++t) {
        const float* l = &h.direct[t * count];
        if (std::all_of(l, l + count, [](float v) { return v == 0; })) continue;
        hours.push_back(t);
        for (const auto& w : page.basis.weights) {
            double sum = 0;
            for (std::size_t s = 0; s < count; ++s) sum += w[s] * double(l[s]);
            weights.push_back(float(sum));
        }
        sun_patch.push_back(h.sun_patch[t]);
        beam.push_back(float(h.beam_luminance[t]));
        sun.push_back({h.sun[t][0], h.sun[t][1], h.sun[t][2], h.sun_lux[t]});
        double seen = 0, omega = 0;
        for (std::size_t s = 1; s < count; ++s)
            seen += double(l[s]) * patches.solid_angle(s), omega += patches.solid_angle(s);
        sky.push_back({float(seen / omega), l[0]});
    }
    return {{"path", page.weather->path},
            {"place", page.weather->place},
            {"hours", hours},
            {"weights", weights},
            {"sun_patch", sun_patch},
            {"beam_luminance", beam},
            {"sun", sun},
            {"sky_ground_luminance", sky}};
}

// What each pane of glass lets through of the sun's beam by the angle it meets it at (33
// steps of cos, as the page's shader reads them).
nlohmann::json pane_tables(const radfmt::MeshData& mesh) {
    nlohmann::json panes = nlohmann::json::object();
    for (const auto& m : mesh.materials)
        if (m.specular.transmits())
            panes[m.name] = rad::luminous_transmittance_by_angle(m.specular, 32);
    return panes;
}

// What the page needs to relight: the place, the sky patches, each component's weights and
// lightmap scale, and how well the basis reproduces a year of clear skies.
nlohmann::json daylight_extras(const Arguments& a, const DaylightPage& page,
                               const rad::BakeResult& result, const radfmt::MeshData& mesh) {
    nlohmann::json components = nlohmann::json::array();
    for (std::size_t k = 0; k < page.basis.values.size(); ++k)
        components.push_back(
            {{"weights", page.basis.weights[k]}, {"scale", result.group_scales[k]}});
    nlohmann::json suns = nlohmann::json::array();
    for (std::size_t k = 0; k < page.sun_patches.size(); ++k)
        suns.push_back({{"patch", page.sun_patches[k]},
                        {"scale", result.group_scales[page.basis.values.size() + k]}});
    nlohmann::json days = nlohmann::json::array();
    for (const auto day : kPageDays) {
        const auto d = rad::Sky::availability(day);
        days.push_back({{"name", d.name},
                        {"parameters", rad::Sky::cie_parameters(d.cie_type)},
                        {"diffuse", d.diffuse},
                        {"extinction", d.extinction}});
    }
    nlohmann::json out = {{"latitude", page.where.latitude},
                          {"longitude", page.where.longitude},
                          {"time_zone", page.where.time_zone},
                          {"north", page.solution.frame.north_deg},
                          {"subdivisions", page.solution.patches.subdivisions()},
                          {"ground", a.ground},
                          {"sky", "each day: its CIE type with the IES daylight availability "
                                  "(diffuse A + B sin(a)^p lux, beam 127500 exp(-c / sin a) "
                                  "lux), the beam in the sky patch it is in"},
                          {"days", days},
                          {"components", components},
                          {"sun_patches", suns},
                          {"mean_error", page.basis.mean_error},
                          {"worst_error", page.basis.worst_error}};
    if (page.weather) out["weather"] = weather_extras(page);
    out["panes"] = pane_tables(mesh);
    return out;
}

// A daylight page's layers: the basis's components, then each sun patch's own group without
// the beam's direct light, which the page traces sharp (its shadows from the sun); what the
// beam's light reflects further stays.
std::vector<std::pair<std::string, std::vector<radfmt::Rgb>>>
daylight_layers(const DaylightPage& page, const radfmt::MeshData& solved) {
    std::vector<std::pair<std::string, std::vector<radfmt::Rgb>>> layers;
    for (std::size_t k = 0; k < page.basis.values.size(); ++k)
        layers.emplace_back("daylight" + std::to_string(k), page.basis.values[k]);
    for (const auto p : page.sun_patches) {
        std::vector<double> only(page.solution.patches.count(), 0.0);
        only[p] = 1;
        auto sun = rad::mix_sky_groups(page.solution, only);
        const auto spread = rad::spread_beam(page.view, solved, p, 1.0);
        for (std::size_t i = 0; i < sun.size(); ++i)
            for (std::size_t c = 0; c < 3; ++c) sun[i][c] = std::max(0.0, sun[i][c] - spread[i][c]);
        layers.emplace_back("sun" + std::to_string(p), std::move(sun));
    }
    return layers;
}

int bake_files(const Arguments& a, const std::string& command) {
    rad::tool::check_outputs({a.mesh_path, a.rad_path}, {{"-o", a.output},
                                                         {"--exr", a.exr},
                                                         {"--png", a.png},
                                                         {"--html", a.html},
                                                         {"--engine", a.engine}});
    const rad::View view = checked_view(a);
    radfmt::OutputBatch outputs; // the glb, the page and the atlas land together or not at all
    rad::ThreadLimit thread_limit(a.threads);
    radfmt::Header mesh_header, rad_header;
    const auto mesh = radfmt::read_mesh(a.mesh_path, &mesh_header);
    const auto radiosity = radfmt::read_radiosity(a.rad_path, &rad_header);
    // Checked first: the daylight page's basis weighs the solution's patches by the mesh's.
    radfmt::require_same_geometry(a.rad_path, rad_header, radiosity.radiosity.size(), a.mesh_path,
                                  mesh, "run rad-ff and rad-solve on " + a.mesh_path + " again");
    const auto daylight = daylight_page(a, mesh, radiosity, rad_header);
    const auto values =
        daylight ? daylight->noon : rad::mix_light_groups(radiosity, a.mix, a.mix_only, a.rad_path);
    radfmt::MeshData solved = mesh; // E and rho as solved, for the exposure
    rad::apply_recorded_overrides(solved, rad_header);
    auto options = bake_options(a, rad::solution_exposure(solved, values));
    if (!a.engine.empty()) options.engine_solved = &solved;
    auto groups = a.lightmap > 0 && !daylight
                      ? group_radiosity(radiosity)
                      : std::vector<std::pair<std::string, std::vector<radfmt::Rgb>>>{};
    if (daylight) {
        options.signed_groups = true;
        groups = daylight_layers(*daylight, solved);
    }
    if (a.lightmap == 0 && radiosity.group_count() > 0 && !a.quiet)
        std::fprintf(stderr,
                     "rad-bake: note: vertex colours hold one mix of the solution's %zu light "
                     "groups; --lightmap keeps one lightmap per group for mixing later\n",
                     radiosity.group_count());

    check_lightmap_memory(a, groups.size());
    auto result = rad::bake(mesh, values, groups, options);
    result.scene.generator = rad::tool_version("rad-bake");
    auto extras =
        provenance_json(mesh_header, a.mesh_path, rad_header, a.rad_path, command, options, result);
    if (daylight) extras["daylight"] = daylight_extras(a, *daylight, result, solved);
    result.scene.extras_json =
        extras.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    const auto glb = rad::baked_glb(result.scene);
    rad::write_file(a.output, glb.data(), glb.size());
    if (!a.html.empty()) {
        const auto page =
            rad::viewer_page(glb, page_config(view, options.exposure), "radiosity: " + a.output);
        rad::write_file(a.html, page.data(), page.size());
    }
    if (!a.engine.empty()) write_engine_glb(a.engine, result, options.exposure);
    std::vector<std::string> group_names;
    for (const auto& g : groups) group_names.push_back(g.first);
    write_atlas_files(a, result, group_names, options.exposure);
    outputs.commit();
    if (!a.quiet) print_summary(a, mesh, result, options.exposure);
    if (daylight && !a.quiet)
        std::fprintf(stderr,
                     "rad-bake: the page relights by date and time from %zu components of the "
                     "solution's %zu sky groups (over a year of clear, partly cloudy and overcast "
                     "days%s at %s the sky's light through them is %.2g%% rms from the full "
                     "solution's on average, %.2g%% at worst) and the groups of the %zu sky "
                     "patches the sun passes through, exactly\n",
                     daylight->basis.values.size(), radiosity.group_count(),
                     daylight->weather ? " and the weather file's hours" : "",
                     a.location.empty() ? daylight->weather->place.c_str() : a.location.c_str(),
                     100 * daylight->basis.mean_error, 100 * daylight->basis.worst_error,
                     daylight->sun_patches.size());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Bake a solution into a binary glTF (.glb) that any glTF viewer shows lit:\n"
                 "smoothed radiosity as vertex colours, or with --lightmap as a texture atlas\n"
                 "on a second UV set (TEXCOORD_1). Materials are KHR_materials_unlit."};
    Arguments arguments;
    add_options(app, arguments);
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::restart_with_huge_pages(argv);
    return rad::tool::run_tool(
        "rad-bake", [&] { return bake_files(arguments, radfmt::command_line(argc, argv)); });
}
