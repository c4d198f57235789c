// rad-shade: mesh + radiosity + view -> linear OpenEXR image (+ PNG preview, PLY mesh).
#include "huge_pages.hpp"
#include "radfmt/chain.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/error.hpp"
#include "radiosity/gathered.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/shade.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/version.hpp"
#include "tool.hpp"

#include <cstdio>
#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"Render per-patch radiosity from a camera (Radiance view options) to a linear\n"
                 "float OpenEXR image, with optional sRGB PNG preview and vertex-coloured PLY."};
    std::string mesh_path, rad_path, output, view_text, view_file, smooth = "crease", png, ply;
    int width = 512, height = 512, aa = 2, threads = 0;
    double exposure = 0, crease = 30;
    bool flat = false, albedo = false, quiet = false;
    app.add_option("MESH", mesh_path, "Patch mesh from rad-mesh")->required();
    app.add_option("RADIOSITY", rad_path, "Radiosity from rad-solve (not needed with --albedo)");
    app.add_option("-o,--output", output, "Output OpenEXR image")->required();
    app.add_option("--view", view_text,
                   "Radiance view options, e.g. \"-vp 0 1 3 -vd 0 0 -1 -vu 0 1 0 -vh 40 -vv 40\"");
    app.add_option("--view-file", view_file,
                   "File with Radiance view options (e.g. scenes/cornell/cornell.vf)");
    app.add_option("-x,--width", width, "Image width in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    app.add_option("-y,--height", height, "Image height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    app.add_option("--aa", aa, "Supersampling: N x N samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    app.add_flag("--flat", flat, "One colour per patch (same as --smooth flat)");
    app.add_option("--smooth", smooth,
                   "crease: area-weighted, not across material or group boundaries or sharp "
                   "edges (each surface keeps its own colour); average: vertex = mean of "
                   "adjacent patches (the paper's, which mixes colours where surfaces meet); "
                   "area: area-weighted; flat")
        ->capture_default_str()
        ->check(CLI::IsMember({"average", "area", "crease", "flat"}));
    app.add_option("--crease-angle", crease,
                   "crease: largest normal angle smoothed across (degrees)")
        ->capture_default_str()
        ->check(rad::tool::finite_range(0, 180));
    app.add_flag("--albedo", albedo,
                 "Show reflectance colours only, flat (the paper's Figure 1(a) and 4)");
    app.add_option("--png", png, "Also write an sRGB tone-mapped PNG preview");
    app.add_option("--ply", ply, "Also write the smoothed mesh with vertex colours as PLY");
    app.add_option("--exposure", exposure,
                   "Linear multiplier for PNG/PLY (default, or 0: from the solution, the same "
                   "for every view: 0.85 over the luminance that 99% of the area of the "
                   "surfaces that do not emit stays below; --albedo: from the image)")
        ->check(rad::tool::finite_range(0, 1e30));
    rad::tool::add_threads_option(app, threads);
    std::vector<std::string> mix;
    bool mix_only = false, layers = false;
    app.add_option("--mix", mix,
                   "Weight a light group (rad-solve --light-groups): NAME=s, or NAME=r,g,b to "
                   "recolour it (repeatable; groups not named keep weight 1)");
    app.add_flag("--mix-only", mix_only, "Groups not named in --mix are off (weight 0)");
    app.add_flag("--layers", layers,
                 "Also write one EXR layer per light group (<group>.R/G/B, each at weight 1, "
                 "for relighting in a compositor) next to the mixed image");
    std::string backfaces = "show";
    app.add_option("--backfaces", backfaces,
                   "Faces seen from behind (the side of a one-sided patch that gets no light): "
                   "show them as they are, or mark them in magenta (a face-orientation overlay)")
        ->capture_default_str()
        ->check(CLI::IsMember({"show", "mark"}));
    std::string max_memory;
    int gather = 0, shadow_rays = 32;
    app.add_option("--gather", gather,
                   "Final gather: each sample is E + rho x the irradiance gathered at the "
                   "visible point with this many indirect rays (direct light sampled on the "
                   "emitters): sharp shadows, no blotches; slower (0: off)")
        ->check(CLI::Range(0, 1000000));
    app.add_option("--shadow-rays", shadow_rays,
                   "--gather: shadow rays per sample for the direct light, shared among the "
                   "lights (emitting patches, and patches lit so brightly that rays landing "
                   "on them would be fireflies) by what each contributes")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    app.add_option("--max-memory", max_memory,
                   "Refuse to start when the images would need more memory than this (e.g. 4G; "
                   "default: 80% of physical memory)");
    app.add_flag("-q,--quiet", quiet, "No summary");
    if (int rc = rad::tool::parse_arguments(app, argc, argv); rc >= 0) return rc;
    rad::tool::restart_with_huge_pages(argv);

    return rad::tool::run_tool("rad-shade", [&] {
        rad::tool::check_outputs({mesh_path, rad_path},
                                 {{"-o", output}, {"--png", png}, {"--ply", ply}});
        // The image, its preview and the PLY land together or not at all.
        radfmt::OutputBatch outputs;
        rad::ThreadLimit thread_limit(threads);
        if (view_text.empty() && view_file.empty())
            throw rad::InputError("give a camera with --view or --view-file");
        rad::View view = view_file.empty() ? rad::View{} : rad::read_view_file(view_file);
        if (!view_text.empty()) view = rad::parse_view(view_text, rad::FileLoc{"--view"}, view);

        radfmt::Header mesh_header, rad_header;
        const auto mesh = radfmt::read_mesh(mesh_path, &mesh_header);
        std::vector<radfmt::Rgb> values;
        radfmt::RadiosityData radiosity;
        std::vector<std::string> chain = mesh_header.chain();
        if (albedo && (!mix.empty() || mix_only || layers))
            throw rad::InputError("--mix, --mix-only and --layers need a radiosity file, not "
                                  "--albedo");
        if (albedo) {
            for (const auto& p : mesh.patches)
                values.push_back(mesh.materials[p.material].reflectance);
            flat = true;
        } else {
            if (rad_path.empty()) throw rad::InputError("give a radiosity file (or use --albedo)");
            radiosity = radfmt::read_radiosity(rad_path, &rad_header);
            values = rad::mix_light_groups(radiosity, mix, mix_only, rad_path);
            if (layers && radiosity.group_count() == 0)
                throw rad::InputError(rad_path + " has no light groups for --layers (solve with "
                                                 "rad-solve --light-groups)");
            radfmt::require_same_geometry(rad_path, rad_header, values.size(), mesh_path, mesh,
                                          "run rad-ff and rad-solve on " + mesh_path + " again");
            chain = rad_header.chain();
        }
        // Checked before rendering: a huge -x/-y/--aa must not eat the machine first.
        const std::uint64_t limit = rad::tool::memory_limit(max_memory);
        const int images = 1 + (layers ? static_cast<int>(radiosity.group_count()) : 0);
        const auto need = rad::estimate_render_memory(width, height, aa, images);
        if (need > limit) {
            std::string message = "a ";
            message += std::to_string(width);
            message += "x";
            message += std::to_string(height);
            message += " image at --aa ";
            message += std::to_string(aa);
            if (images > 1) {
                message += " with ";
                message += std::to_string(images - 1);
                message += " layers";
            }
            message += " needs about " + rad::human_bytes(double(need)) +
                       ", more than --max-memory " + rad::human_bytes(double(limit)) +
                       " (use a smaller -x/-y or --aa)";
            throw rad::InputError(message);
        }
        const auto mode = flat ? rad::Smoothing::Flat : rad::parse_smoothing(smooth);
        const auto corners = rad::corner_colours(mesh, values, mode, crease);
        // E and rho as solved (rad-solve's overrides are in the file's header): for the gather
        // and the exposure.
        radfmt::MeshData solved;
        if (!albedo) {
            solved = mesh;
            rad::apply_recorded_overrides(solved, rad_header);
        }
        rad::Image image;
        if (gather > 0) {
            if (albedo || !mix.empty() || mix_only || layers)
                throw rad::InputError("--gather shades a solution as solved: not with --albedo, "
                                      "--mix, --mix-only or --layers");
            rad::GatherOptions options;
            options.rays = gather;
            options.shadow_rays = shadow_rays;
            options.smoothing = mode;
            options.crease_deg = crease;
            const rad::Gatherer gatherer(solved, values, options);
            image = rad::render_gathered(gatherer, view, width, height, aa, quiet);
        } else {
            image = rad::render(mesh, corners, view, width, height, aa);
        }
        if (image.covered_pixels == 0)
            throw rad::InputError(
                "the view sees no geometry of " + mesh_path +
                " (camera outside looking away, or inside an object facing nothing)");

        // Exposure from the solution (every view of it alike; lamps in view do not set it), or
        // for albedo from the image; then the overlay in full magenta at that exposure.
        double scale = exposure;
        if (!(scale > 0) && !albedo) scale = rad::solution_exposure(solved, values);
        if (!(scale > 0)) scale = rad::auto_exposure(image);
        if (backfaces == "mark") rad::mark_back_faces(image, {1 / scale, 0, 1 / scale});
        const double back_share = double(image.back_face_pixels) / (double(width) * height);
        if (back_share > 0.01)
            std::fprintf(stderr,
                         "rad-shade: warning: %.1f%% of the image shows the back of surfaces "
                         "(they get no light from this side: they probably face the wrong way%s; "
                         "see rad-mesh --orient fix, --flip, --two-sided)\n",
                         100 * back_share,
                         backfaces == "mark" ? ", marked in magenta"
                                             : ", --backfaces mark shows where");

        std::map<std::string, std::string> attributes;
        std::string provenance;
        for (std::size_t i = 0; i < chain.size(); ++i)
            provenance += std::to_string(i + 1) + ". " + chain[i] + "\n";
        provenance +=
            std::to_string(chain.size() + 1) + ". " + radfmt::command_line(argc, argv) + "\n";
        attributes["radiosity:provenance"] = provenance;
        attributes["radiosity:tool"] = rad::tool_version("rad-shade");
        attributes["radiosity:mesh"] = mesh_path + " " + mesh_header.file_hash;
        if (!albedo) attributes["radiosity:radiosity"] = rad_path + " " + rad_header.file_hash;
        attributes["radiosity:units"] = albedo ? "reflectance" : "radiosity W/m^2 (linear)";
        // One image per light group for --layers, each at weight 1.
        std::vector<rad::Image> group_images;
        std::vector<rad::ImageLayer> exr_layers;
        if (layers) {
            group_images.reserve(radiosity.group_count());
            for (std::size_t g = 0; g < radiosity.group_count(); ++g) {
                std::vector<radfmt::Rgb> group_values(radiosity.radiosity.size());
                for (std::size_t i = 0; i < group_values.size(); ++i)
                    group_values[i] = radiosity.of_group(i, g);
                group_images.push_back(
                    rad::render(mesh, rad::corner_colours(mesh, group_values, mode, crease), view,
                                width, height, aa));
            }
            for (std::size_t g = 0; g < group_images.size(); ++g)
                exr_layers.push_back({radiosity.group_names[g], &group_images[g]});
        }
        if (!mix.empty() || mix_only) {
            std::string text;
            for (const auto& m : mix) text += (text.empty() ? "" : " ") + m;
            attributes["radiosity:mix"] = (mix_only ? "only " : "") + text;
        }
        rad::write_exr(output, image, attributes, exr_layers);
        if (!png.empty()) rad::write_png(png, image, scale);
        if (!ply.empty()) rad::write_ply(ply, mesh, corners, scale);
        outputs.commit();
        if (!quiet)
            std::fprintf(stderr, "rad-shade: wrote %s (%dx%d, %s%s), exposure %.4g\n",
                         output.c_str(), width, height,
                         albedo ? "albedo"
                         : flat ? "flat"
                                : smooth.c_str(),
                         png.empty() ? "" : ", png", scale);
        return 0;
    });
}
