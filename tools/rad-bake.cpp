// rad-bake: mesh + radiosity -> binary glTF with the light baked in (vertex colours or a
// lightmap atlas), plus the atlas as linear EXR and sRGB PNG.
#include "huge_pages.hpp"
#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/bake.hpp"
#include "radiosity/error.hpp"
#include "radiosity/image_io.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/version.hpp"
#include "radiosity/view.hpp"
#include "tool.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace {

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
    return config.dump();
}

rad::Image lightmap_image(const rad::Lightmap& map) {
    rad::Image image;
    image.width = image.height = map.size;
    image.rgb = map.rgb;
    return image;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Bake a solution into a binary glTF (.glb) that any glTF viewer shows lit:\n"
                 "smoothed radiosity as vertex colours, or with --lightmap as a texture atlas\n"
                 "on a second UV set (TEXCOORD_1). Materials are KHR_materials_unlit."};
    std::string mesh_path, rad_path, output, smooth = "crease", exr, png, html, view_text,
                                             view_file;
    double crease = 30, exposure = 0, density = 0, chart_angle = 20;
    int lightmap = 0, padding = 2, threads = 0;
    bool quiet = false, mix_only = false;
    std::vector<std::string> mix;
    app.add_option("MESH", mesh_path, "Patch mesh from rad-mesh")->required();
    app.add_option("RADIOSITY", rad_path, "Radiosity from rad-solve")->required();
    app.add_option("-o,--output", output, "Output binary glTF (.glb)")->required();
    app.add_option("--smooth", smooth, "Smoothing, as rad-shade's --smooth")
        ->capture_default_str()
        ->check(CLI::IsMember({"average", "area", "crease", "flat"}));
    app.add_option("--crease-angle", crease, "crease: largest normal angle smoothed across")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 180));
    app.add_option("--exposure", exposure,
                   "Linear multiplier from W/m^2 to display values (default, or 0: rad-shade's "
                   "exposure from the solution, so the glb looks like rad-shade's image)")
        ->check(rad::tool::finite_range(0, 1e30));
    app.add_option("--mix", mix, "Weight a light group, as rad-shade --mix (repeatable)");
    app.add_flag("--mix-only", mix_only, "Groups not named in --mix are off");
    app.add_option("--lightmap", lightmap,
                   "Bake a SIZE x SIZE lightmap atlas instead of vertex colours (e.g. 1024)")
        ->check(CLI::Range(8, 16384));
    app.add_option("--texels-per-metre", density,
                   "--lightmap: texel density (default: the highest at which the charts fit)")
        ->check(rad::tool::finite_range(0, 1e9));
    app.add_option("--padding", padding,
                   "--lightmap: texels around each chart, filled from its edge so bilinear "
                   "filtering never reads a neighbour")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    app.add_option("--chart-angle", chart_angle,
                   "--lightmap: largest angle between normals within one chart (degrees)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 60));
    app.add_option("--exr", exr,
                   "--lightmap: also write the atlas as linear float OpenEXR (radiosity, W/m^2; "
                   "one layer per light group)");
    app.add_option("--png", png, "--lightmap: also write the atlas as sRGB PNG (as in the glb)");
    app.add_option("--html", html,
                   "Also write a self-contained viewer page (three.js): the glb from the camera "
                   "of --view/--view-file at the same exposure, orbit controls, an exposure "
                   "slider and with light groups one slider per group (needs --lightmap)");
    app.add_option("--view", view_text, "--html: the camera, as rad-shade's --view");
    app.add_option("--view-file", view_file, "--html: the camera, as rad-shade's --view-file");
    rad::tool::add_threads_option(app, threads);
    app.add_flag("-q,--quiet", quiet, "No summary");
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::tool::restart_with_huge_pages(argv);

    return rad::tool::run_tool("rad-bake", [&] {
        rad::tool::check_outputs(
            {mesh_path, rad_path},
            {{"-o", output}, {"--exr", exr}, {"--png", png}, {"--html", html}});
        if (lightmap == 0 && (!exr.empty() || !png.empty() || density > 0))
            throw rad::InputError("--exr, --png and --texels-per-metre need --lightmap SIZE");
        if (!html.empty() && view_text.empty() && view_file.empty())
            throw rad::InputError("--html needs a camera: give --view or --view-file");
        if (html.empty() && !(view_text.empty() && view_file.empty()))
            throw rad::InputError("--view and --view-file are for the --html page");
        rad::View view = view_file.empty() ? rad::View{} : rad::read_view_file(view_file);
        if (!view_text.empty()) view = rad::parse_view(view_text, rad::FileLoc{"--view"}, view);
        radfmt::OutputBatch outputs;
        rad::ThreadLimit thread_limit(threads);
        radfmt::Header mesh_header, rad_header;
        const auto mesh = radfmt::read_mesh(mesh_path, &mesh_header);
        const auto radiosity = radfmt::read_radiosity(rad_path, &rad_header);
        const auto values = rad::mix_light_groups(radiosity, mix, mix_only, rad_path);
        radfmt::require_same_geometry(rad_path, rad_header, values.size(), mesh_path, mesh,
                                      "run rad-ff and rad-solve on " + mesh_path + " again");
        radfmt::MeshData solved = mesh;
        rad::apply_recorded_overrides(solved, rad_header);

        rad::BakeOptions options;
        options.smoothing = rad::parse_smoothing(smooth);
        options.crease_deg = crease;
        options.exposure = exposure > 0 ? exposure : rad::solution_exposure(solved, values);
        if (!(options.exposure > 0)) options.exposure = 1;
        options.lightmap_size = lightmap;
        options.texels_per_metre = density;
        options.padding = padding;
        options.chart_angle_deg = chart_angle;
        std::vector<std::pair<std::string, std::vector<radfmt::Rgb>>> groups;
        if (lightmap > 0)
            for (std::size_t g = 0; g < radiosity.group_count(); ++g) {
                std::vector<radfmt::Rgb> group(radiosity.radiosity.size());
                for (std::size_t i = 0; i < group.size(); ++i) group[i] = radiosity.of_group(i, g);
                groups.emplace_back(radiosity.group_names[g], std::move(group));
            }
        auto result = rad::bake(mesh, values, groups, options);
        result.scene.generator = rad::tool_version("rad-bake");
        result.scene.extras_json =
            provenance_json(mesh_header, mesh_path, rad_header, rad_path,
                            radfmt::command_line(argc, argv), options, result)
                .dump();
        const auto glb = rad::baked_glb(result.scene);
        rad::write_file(output, glb.data(), glb.size());
        if (!html.empty()) {
            const auto page =
                rad::viewer_page(glb, page_config(view, options.exposure), "radiosity: " + output);
            rad::write_file(html, page.data(), page.size());
        }
        if (!exr.empty()) {
            const auto main_image = lightmap_image(result.lightmap);
            std::vector<rad::Image> group_images;
            std::vector<rad::ImageLayer> layers;
            for (const auto& map : result.group_lightmaps)
                group_images.push_back(lightmap_image(map));
            for (std::size_t g = 0; g < group_images.size(); ++g)
                layers.push_back({groups[g].first, &group_images[g]});
            rad::write_exr(exr, main_image,
                           {{"radiosity:tool", rad::tool_version("rad-bake")},
                            {"radiosity:units", "radiosity W/m^2 (linear)"},
                            {"radiosity:glb", output}},
                           layers);
        }
        if (!png.empty())
            rad::write_png_rgb8(png, result.layout.size, result.layout.size,
                                rad::lightmap_pixels(result.lightmap, options.exposure));
        outputs.commit();
        if (!quiet) {
            if (lightmap > 0)
                std::fprintf(stderr,
                             "rad-bake: wrote %s (%zu patches, %zu charts in a %dx%d lightmap at "
                             "%.4g texels/m%s), exposure %.4g\n",
                             output.c_str(), mesh.patches.size(), result.charts, lightmap, lightmap,
                             result.layout.texels_per_metre,
                             groups.empty() ? "" : ", one lightmap per light group",
                             options.exposure);
            else
                std::fprintf(stderr,
                             "rad-bake: wrote %s (%zu patches, vertex colours), exposure %.4g\n",
                             output.c_str(), mesh.patches.size(), options.exposure);
        }
        return 0;
    });
}
