// A mutation fuzzer over every reader: chain files (mesh, form factors, radiosity) mutated
// inside their body and header fields and then given correct checksums again, so the
// mutations reach the value checks behind the checksums; and OBJ/MTL text mutated with the
// tokens readers get wrong (nan, 0x, huge exponents, stray slashes). Every read must end in
// a result or a clear refusal (FormatError, InputError); what is read is then used (ray
// scene, form factors, a solve, smoothing) to show that a refusal-free read is safe to use.
// Built with ASan+UBSan (RADIOSITY_SANITIZE) it runs in CI; deterministic for a seed.
//
// Imports too (glTF, GLB, PLY ascii and binary, COLLADA, STL, FBX ascii: the Cornell box
// exported by assimp, mutated as bytes): each read through rad-mesh's import path, where
// assimp runs isolated, so a crash or hang of assimp's own is a refusal naming the file; the
// run counts those apart.
//
//   fuzz_readers DATA_DIR [--iterations N] [--seconds S] [--seed K] [--kind NAME[,NAME...]]
//                [--min-cases N]
#include "../helpers.hpp"
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/hierarchy.hpp"
#include "radiosity/light_groups.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/melanopic.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/report.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/solver.hpp"
#include "radiosity/transport.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Bytes = std::string;

Bytes read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// A chain file split into its header lines (without the checksum line) and its body.
struct Container {
    std::vector<std::string> lines;
    Bytes body;
};

Container split(const Bytes& file) {
    Container c;
    const auto hash_line = file.find("\nheader_hash=");
    const auto blank = file.find("\n\n", hash_line + 1);
    std::size_t start = 0;
    while (start <= hash_line) {
        const auto end = file.find('\n', start);
        c.lines.push_back(file.substr(start, end - start));
        start = end + 1;
    }
    const auto offset =
        (blank + 2 + radfmt::kBodyAlignment - 1) / radfmt::kBodyAlignment * radfmt::kBodyAlignment;
    c.body = file.substr(std::min(offset, file.size()));
    return c;
}

// Serialises with a correct body size, body hash and header hash: only the values are off.
Bytes join(Container c) {
    std::string text;
    for (auto& line : c.lines) {
        if (line.rfind("body_size=", 0) == 0) line = "body_size=" + std::to_string(c.body.size());
        if (line.rfind("body_hash=", 0) == 0)
            line = "body_hash=xxh64:" +
                   radfmt::hash_hex(radfmt::hash_bytes(c.body.data(), c.body.size()));
        text += line + "\n";
    }
    text += "header_hash=xxh64:" + radfmt::hash_hex(radfmt::hash_bytes(text.data(), text.size())) +
            "\n\n";
    text.resize((text.size() + radfmt::kBodyAlignment - 1) / radfmt::kBodyAlignment *
                    radfmt::kBodyAlignment,
                '\0');
    return text + c.body;
}

class Mutator {
  public:
    explicit Mutator(std::uint64_t seed) : rng_(seed) {}
    std::size_t below(std::size_t n) {
        return n ? std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_) : 0;
    }
    bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }

    template <class T> void put(Bytes& body, std::size_t align, T value) {
        if (body.size() < sizeof(T)) return;
        const auto at = below((body.size() - sizeof(T)) / align + 1) * align;
        std::memcpy(body.data() + at, &value, sizeof(T));
    }

    void mutate_body(Bytes& body) {
        static const double doubles[] = {std::numeric_limits<double>::quiet_NaN(),
                                         std::numeric_limits<double>::infinity(),
                                         -std::numeric_limits<double>::infinity(),
                                         -1.0,
                                         0.0,
                                         -0.0,
                                         1e308,
                                         1e-310,
                                         2.0,
                                         1e30};
        static const float floats[] = {std::numeric_limits<float>::quiet_NaN(),
                                       std::numeric_limits<float>::infinity(),
                                       -1.0f,
                                       0.0f,
                                       1.5f,
                                       3.0e38f,
                                       1e-45f};
        static const std::uint32_t words[] = {0,          1,          2,      3,      0xFFFFFFFF,
                                              0x7FFFFFFF, 0x80000000, 0xFFFF, 1000000};
        static const std::uint64_t longs[] = {0, 1, 0xFFFFFFFFFFFFFFFFull, 0x100000000ull,
                                              1ull << 62};
        switch (below(7)) {
        case 0:
            if (!body.empty()) body[below(body.size())] ^= static_cast<char>(1u << below(8));
            break;
        case 1:
            put(body, 8, doubles[below(std::size(doubles))]);
            break;
        case 2:
            put(body, 4, floats[below(std::size(floats))]);
            break;
        case 3:
            put(body, 4, words[below(std::size(words))]);
            break;
        case 4:
            put(body, 8, longs[below(std::size(longs))]);
            break;
        case 5:
            body.resize(below(body.size() + 1)); // truncated
            break;
        default:
            body.append(1 + below(64), static_cast<char>(below(256))); // extended
        }
    }

    void mutate_header(std::vector<std::string>& lines) {
        static const char* values[] = {"",  "-1", "nan", "1e999", "18446744073709551616",
                                       "0", "1",  "2",   "inf",   "99999999999999999999",
                                       "x", "-0", " 3",  "0x10",  "1e-400"};
        std::vector<std::size_t> editable;
        for (std::size_t i = 0; i < lines.size(); ++i)
            if (lines[i].rfind("field.", 0) == 0 || lines[i].rfind("version=", 0) == 0)
                editable.push_back(i);
        if (editable.empty()) return;
        auto& line = lines[editable[below(editable.size())]];
        const auto eq = line.find('=');
        line = line.substr(0, eq + 1) + values[below(std::size(values))];
    }

    // Replaces the file a reference names (a glTF "uri", an OBJ mtllib, an MTL map_Kd) by a
    // path that reaches outside the scene's folder in one of the forms importers decode, or a
    // device: each must be refused, never read (#55 item 1).
    void mutate_path(std::string& text) {
        static const char* paths[] = {
            "../secret.bin",      "..\\secret.bin",  "%2e%2e/secret.bin",
            "..%2fsecret.bin",    "..%5csecret.bin", "file:../secret.bin",
            "file:///etc/passwd", "/etc/passwd",     "C:\\x.bin",
            "x/../../secret.bin", "/dev/zero",       "..\\..\\..\\etc\\passwd"};
        std::vector<std::pair<std::size_t, std::size_t>> values; // (start, length)
        for (const char* key : {"\"uri\"", "mtllib ", "map_Kd "}) {
            for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
                auto start = at + std::strlen(key);
                if (key[0] == '"') { // "uri": "VALUE"
                    start = text.find('"', text.find(':', start));
                    if (start == std::string::npos) continue;
                    ++start;
                    const auto end = text.find('"', start);
                    if (end != std::string::npos) values.push_back({start, end - start});
                } else {
                    const auto end = text.find_first_of("\r\n", start);
                    values.push_back(
                        {start, (end == std::string::npos ? text.size() : end) - start});
                }
            }
        }
        if (values.empty()) return;
        const auto [start, length] = values[below(values.size())];
        text.replace(start, length, paths[below(std::size(paths))]);
    }

    // A glTF's instancing made heavy: its first node's mesh placed at up to 4000 new nodes
    // (each a root of the scene), so the importer must count instances before building them.
    void mutate_instances(std::string& text) {
        auto doc = nlohmann::json::parse(text, nullptr, false);
        if (doc.is_discarded() || !doc.is_object() || !doc.contains("nodes") ||
            !doc["nodes"].is_array() || doc["nodes"].empty() || !doc.contains("scenes") ||
            !doc["scenes"].is_array() || doc["scenes"].empty() || !doc["scenes"][0].is_object())
            return;
        nlohmann::json mesh_node;
        for (const auto& node : doc["nodes"])
            if (node.is_object() && node.contains("mesh")) mesh_node = {{"mesh", node["mesh"]}};
        if (mesh_node.is_null()) return;
        const auto copies = 1 + below(4000);
        auto& roots = doc["scenes"][0]["nodes"];
        if (!roots.is_array()) return;
        for (std::size_t k = 0; k < copies; ++k) {
            auto node = mesh_node;
            node["translation"] = {double(k % 64), 0.0, double(k / 64)};
            roots.push_back(doc["nodes"].size());
            doc["nodes"].push_back(node);
        }
        text = doc.dump();
    }

    void mutate_text(std::string& text) {
        if (below(4) == 0) mutate_path(text);
        if (below(8) == 0) mutate_instances(text);
        static const char* tokens[] = {
            "nan",          "inf", "-",   "0x2",         "1e999", "/", "//", " ",
            "\n",           "#",   "v ",  "f ",          "-1",    "0", "\t", "1e-320",
            "\xEF\xBB\xBF", "Kd ", "Ke ", "99999999999", ".",     "e", "\0"};
        const auto edits = 1 + below(4);
        for (std::size_t k = 0; k < edits; ++k) {
            const char* chosen = tokens[below(std::size(tokens))];
            const std::string insert = *chosen ? std::string(chosen) : std::string(1, '\0');
            const auto at = below(text.size() + 1);
            switch (below(3)) {
            case 0:
                text.insert(at, insert);
                break;
            case 1:
                text.replace(at, std::min<std::size_t>(1 + below(6), text.size() - at), insert);
                break;
            default:
                text.erase(at, std::min<std::size_t>(1 + below(8), text.size() - at));
            }
        }
    }

  private:
    std::mt19937_64 rng_;
};

// Outcomes: a clean read, a clear refusal, or a failure (anything else) that stops the run.
struct Tally {
    std::size_t read = 0, refused = 0, importer_failed = 0;
};

bool expected_refusal(const std::function<void()>& body, Tally& tally, std::string& failure) {
    try {
        body();
        ++tally.read;
    } catch (const radfmt::FormatError&) {
        ++tally.refused;
    } catch (const rad::InputError& e) {
        ++tally.refused;
        if (std::strstr(e.what(), "the importer (assimp) failed")) ++tally.importer_failed;
    } catch (const std::exception& e) {
        failure = std::string("unexpected exception: ") + e.what();
        return false;
    }
    return true;
}

// Uses what a reader accepted, as the tools would.
void use_mesh(const radfmt::MeshData& mesh) {
    if (mesh.patches.empty()) return;
    rad::check_ray_precision(mesh.vertices, "mesh");
    rad::FormFactorOptions options;
    options.method = "hemisphere";
    options.rays = 16;
    options.quiet = true;
    rad::compute_form_factors(mesh, options);
    rad::corner_colours(mesh, std::vector<radfmt::Rgb>(mesh.patches.size(), {0.5, 0.5, 0.5}),
                        rad::Smoothing::Crease);
}

void use_form_factors(const radfmt::MeshData& mesh, const radfmt::FormFactorData& ff) {
    if (ff.patch_count != mesh.patches.size()) return;
    const auto op = rad::make_operator(mesh, ff);
    rad::SolveControl control;
    control.max_iterations = 3;
    for (const char* method : {"gs", "pr"})
        rad::solver(method).solve(op, rad::emission_of(mesh), control);
}

// A links file is trusted by the sweep once read: every index it follows must be checked.
void use_links(const radfmt::MeshData& mesh, const radfmt::LinkData& links) {
    if (links.patch_count != mesh.patches.size()) return;
    const auto op = rad::make_operator(mesh, links);
    rad::SolveControl control;
    control.max_iterations = 3;
    for (const char* method : {"gs", "jacobi"})
        rad::solver(method).solve(op, rad::emission_of(mesh), control);
    rad::link_row_sums(mesh, links);
}

void use_radiosity(const radfmt::MeshData& mesh, const radfmt::RadiosityData& rad_data) {
    const auto values = rad_data.group_count() ? rad::mix_light_groups(rad_data, {}, false, "rad")
                                               : rad_data.radiosity;
    if (values.size() == mesh.patches.size())
        rad::corner_colours(mesh, values, rad::Smoothing::Average);
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: fuzz_readers DATA_DIR [--iterations N] [--seconds S] [--seed K] "
                     "[--kind NAME[,NAME...]] [--min-cases N]\n  kinds: mesh formfactors "
                     "links radiosity luminaires ies ldt sky annual epw calc spectrum obj mtl gltf "
                     "glb ply "
                     "plyb dae stl fbx\n";
        return 1;
    }
    const fs::path data = argv[1];
    long iterations = 2000;
    double seconds = 30;
    std::uint64_t seed = 1;
    std::string only;   // ",name,name,": the kinds to run (all when empty)
    long min_cases = 0; // a kind stopped by --seconds before this many cases fails
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string option = argv[i];
        if (option == "--iterations")
            iterations = std::stol(argv[i + 1]);
        else if (option == "--seconds")
            seconds = std::stod(argv[i + 1]);
        else if (option == "--seed")
            seed = std::stoull(argv[i + 1]);
        else if (option == "--kind")
            only = "," + std::string(argv[i + 1]) + ",";
        else if (option == "--min-cases")
            min_cases = std::stol(argv[i + 1]);
        else {
            std::cerr << "fuzz_readers: unknown option " << option << "\n";
            return 1;
        }
    }
    const auto dir = fs::temp_directory_path() / ("radiosity-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(dir);

    // Seeds: a real public scene through the real chain, kept small.
    const fs::path obj = data / "cornell-original" / "CornellBox-Original.obj";
    const fs::path mtl = data / "cornell-original" / "CornellBox-Original.mtl";
    auto scene = rad::load_scene(obj);
    rad::remove_duplicate_faces(scene);
    rad::SubdivisionOptions subdivision;
    subdivision.max_edge = 0.6;
    const auto mesh = rad::subdivide(scene, subdivision);
    rad::FormFactorOptions ff_options;
    ff_options.method = "hemisphere";
    ff_options.rays = 64;
    ff_options.quiet = true;
    const auto ff = rad::compute_form_factors(mesh, ff_options);
    const auto op = rad::make_operator(mesh, ff);
    rad::SolveControl control;
    control.max_iterations = 5;
    const auto solution = rad::solver("gs").solve(op, rad::emission_of(mesh), control).radiosity;
    radfmt::Header header;
    header.tool = "fuzz_readers";
    header.command = "fuzz_readers";
    radfmt::write_mesh(dir / "seed.mesh", header, mesh);
    // With the method's fields, so that the rows are hit counts (rad-solve then packs them).
    radfmt::Header ff_header = header;
    for (const auto& [key, value] : rad::form_factor_header_fields(ff_options))
        ff_header.set(key, value);
    radfmt::write_form_factors(dir / "seed.ff", ff_header, ff);
    radfmt::write_radiosity(dir / "seed.rad", header, rad::radiosity_data(solution, {}));
    radfmt::write_links(dir / "seed.links", header, rad::compute_links(mesh, {}));
    // A mesh of version 2: an L-shaped polygon patch (not convex, star-shaped from its first
    // corner) under a square quad.
    radfmt::write_mesh(
        dir / "seed-polygon.mesh", header,
        testing_helpers::polygon_under_square({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 3,
                                              {5.0 / 6, 5.0 / 6, 0}));
    // A mesh of version 3: the box with a mirror and a glass block (specular parts), which
    // use_mesh's rays follow.
    auto specular = mesh;
    for (std::size_t m = 0; m < specular.materials.size(); ++m) {
        auto& part = specular.materials[m].specular;
        if (m % 3 == 1) part = {radfmt::SpecularKind::mirror, {{0.9, 0.9, 0.9}}, {}, 1.5, 0};
        if (m % 3 == 2) part = {radfmt::SpecularKind::dielectric, {}, {{1, 1, 1}}, 1.5, 0.1};
    }
    radfmt::write_mesh(dir / "seed-specular.mesh", header, specular);
    // A second radiosity seed with light groups (version 2's extra arrays).
    rad::Channels grouped(mesh.patches.size(), 6);
    for (auto& v : grouped.values) v = 0.25;
    radfmt::write_radiosity(dir / "seed-groups.rad", header,
                            rad::radiosity_data(grouped, {{"a", {}}, {"b", {}}}));

    // A luminaires file: the ERCO downlight over the box, its layout and IES text inside.
    const fs::path ies = data / "photometry" / "photon-v2_ERCO_Panarc_corridor_1.ies";
    const fs::path ldt = data / "photometry" / "eulumdat-ugr_sample_01_Isym4.ldt";
    {
        const auto text = read_bytes(ies);
        const rad::LuminaireSources sources{
            "layout.csv",
            "name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group\n"
            "a,erco.ies,0,1.5,0,,,,30,0.8,\nb,erco.ies,0.3,1.5,0,0,-1,1,,,\n",
            {{"erco.ies", std::string(text.begin(), text.end())}}};
        const auto set = rad::build_luminaires(sources, 1);
        const rad::RayScene lum_scene(mesh);
        radfmt::write_luminaires(
            dir / "seed.lum", header,
            {sources.layout_name, sources.layout_text, sources.files, set.groups,
             mesh.patches.size(),
             rad::patch_direct_light(mesh, set, lum_scene, 0, mesh.patches.size())});
    }
    // What a tool does with a luminaires file: rebuild the luminaires from the texts inside,
    // and light a point with them.
    const auto use_luminaires = [&](const radfmt::LuminaireData& lum) {
        const auto set = rad::build_luminaires({lum.layout_name, lum.layout_text, lum.files}, 1);
        for (const auto& l : set.luminaires) (void)set.flux(l);
        (void)rad::luminaire_irradiance(set, {0, 0.5, 0}, {0, 1, 0}, nullptr);
    };
    const auto use_photometry = [](const fs::path& p, const std::string& name) {
        const auto bytes = read_bytes(p);
        const auto photometry =
            rad::parse_photometry(std::string(bytes.begin(), bytes.end()), name, nullptr);
        (void)photometry.flux();
        (void)rad::flux_warnings(photometry);
        (void)photometry.intensity(33, 47);
    };

    // Daylight: a .sky of the box (its view of Tregenza's sky), a year at two sensors, and
    // the Denver EPW (tests/data).
    const fs::path epw = data / "denver-tmy3.epw";
    {
        const rad::RayScene sky_scene(mesh);
        const rad::SpecularSurfaces sky_specular(mesh);
        const rad::SkyViewOptions options{rad::SkyPatches(1), rad::SkyFrame{15}, 64, 1, 12};
        const auto view =
            rad::patch_sky_view(mesh, sky_scene, sky_specular, options, 0, mesh.patches.size());
        radfmt::SkyData sky{"reinhart:1", 15, mesh.patches.size(), options.patches.count(), {}};
        for (const auto& c : view)
            for (double v : c) sky.coefficients.push_back(float(v));
        radfmt::write_sky(dir / "seed.sky", header, sky);
        radfmt::AnnualData year;
        year.positions = {{0, 0.5, 0}, {0.2, 0.5, 0.1}};
        year.normals = {{0, 1, 0}, {1, 0, 0}};
        for (std::uint32_t h = 0; h < 48; ++h) {
            year.hours.push_back(10000 + (1 + h / 24) * 100 + h % 24 + 1);
            year.occupied.push_back(h % 24 >= 8 && h % 24 < 18);
            year.lux.insert(year.lux.end(), {float(h * 40), float(h * 20)});
            year.sun_lux.insert(year.sun_lux.end(), {float(h * 25), 0});
        }
        radfmt::write_annual(dir / "seed.ill", header, year);
    }
    // What rad-solve does with a .sky (each sky patch's first bounce on the mesh it belongs
    // to), and rad-gather with a year and a weather file.
    const auto use_sky = [&](const radfmt::SkyData& sky) {
        const auto patches = rad::SkyPatches::parse(sky.subdivision);
        if (patches.count() != sky.sky_patches || sky.patch_count != mesh.patches.size()) return;
        double total = 0;
        for (std::size_t i = 0; i < sky.patch_count; ++i)
            for (std::size_t k = 0; k < sky.sky_patches; ++k)
                total += rad::luminous(sky.of(i, k)) * mesh.patches[i].area;
        if (!std::isfinite(total)) throw std::logic_error("a .sky read with a value not finite");
    };
    const auto use_weather = [](const fs::path& p) {
        const auto weather = rad::read_epw(p.string());
        for (std::size_t t = 0; t < weather.hours.size(); t += 97) {
            const auto& h = weather.hours[t];
            const auto sun = rad::sun_of_hour(weather, h);
            const auto sky = rad::Sky::perez(h.direct_normal, h.diffuse_horizontal, sun,
                                             h.day_of_year(), h.dew_point, rad::SkyFrame{}, 0.2);
            if (!std::isfinite(sky.horizontal_illuminance()) ||
                !std::isfinite(sky.sun_normal_illuminance()))
                throw std::logic_error("a sky of the weather file is not finite");
        }
    };

    // A calculation-surfaces file (rad-gather --surfaces, rad-report): its grids, and the
    // report's page of made-up values on them (hostile names, sizes and numbers reach the
    // page's plans, isolines and escaping).
    const std::string calc_seed =
        "name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing,border,Em,U0,Emin,UGRL,angle\n"
        "work plane,workplane,0,0.8,4,6,0,0,0,0,-4,,,500,0.6,,,\n"
        "\"desk, <east>\",task,2.2,0.72,2.4,1.6,0,0,0,0,-0.8,0.1,,500,0.6,,,\n"
        "south wall,wall,0,0,0,6,0,0,0,3,0,,0.2,50,0.1,20,,\n"
        "desk chair,observer,3,1.2,3.6,0,0,-1,,,,,,,,,19,\n"
        "door,camera,0.3,1.6,0.3,1,-0.1,0.7,,,,,,,,,,85\n";
    // A spectrum (rad-gather --spectrum FILE): a lamp's relative power every few nanometres,
    // weighed as melanopic EDI is.
    const std::string spectrum_seed = "wavelength_nm,power\n# a warm LED\n380,0.01\n420,0.05\n"
                                      "450,0.62\n480,0.18\n520,0.42\n580,0.95\n620,1\n"
                                      "680,0.55\n730,0.2\n780,0.05\n";
    const auto use_spectrum = [](const fs::path& p) {
        const auto s = rad::read_spectrum_csv(p.string());
        const double der = rad::melanopic_der(s);
        if (!std::isfinite(der) || der < 0)
            throw std::logic_error("a spectrum read gives mel-DER " + std::to_string(der));
        (void)rad::melanopic_weights(s, {1, 1, 1});
    };
    const auto use_calc = [](const fs::path& p) {
        const auto file = rad::read_calc_file(p.string());
        rad::ReportInput in;
        long sensors = 0;
        for (const auto& surface : file.surfaces) {
            rad::ReportSurface s;
            s.surface = surface;
            s.grid = rad::surface_grid(surface, 1);
            if ((sensors += s.grid.size()) > 200000) return; // a big grid is not a hostile one
            for (long k = 0; k < s.grid.size(); ++k) {
                const auto x = s.grid.position(k);
                s.lux.push_back(k % 7 == 3 ? std::nan("") : 100 + 50 * std::sin(x[0] + 2 * x[2]));
            }
            s.stats = rad::illuminance_stats(s.lux);
            s.verdict = rad::judge(s.stats, surface.required);
            in.surfaces.push_back(std::move(s));
        }
        if (rad::report_html(in).find("</html>") == std::string::npos)
            throw std::logic_error("the report's page has no end");
    };

    struct Kind {
        std::string name;
        std::vector<Bytes> seeds;
        bool text;
        std::function<void(const fs::path&)> read_and_use;
    };
    const auto mesh_copy = mesh;
    // Import seeds: the Cornell box exported by assimp in each format; extra files a format
    // writes beside it (the glTF's .bin) are copied next to every mutant.
    struct ImportSeed {
        std::string kind, format, extension;
    };
    const ImportSeed import_seeds[] = {{"gltf", "gltf2", ".gltf"}, {"glb", "glb2", ".glb"},
                                       {"ply", "ply", ".ply"},     {"plyb", "plyb", ".ply"},
                                       {"dae", "collada", ".dae"}, {"stl", "stlb", ".stl"},
                                       {"fbx", "fbxa", ".fbx"}};
    const fs::path export_dir = dir / "exports";
    fs::create_directories(export_dir);
    for (const auto& seed_format : import_seeds) { // a fresh import for every export
        Assimp::Importer importer;
        // Triangulated: assimp 5.2's exporters corrupt the heap on the box's quads.
        const aiScene* source = importer.ReadFile(obj.string(), aiProcess_JoinIdenticalVertices |
                                                                    aiProcess_Triangulate);
        if (!source) throw std::runtime_error("cannot read the import seed " + obj.string());
        Assimp::Exporter exporter;
        const auto target = export_dir / ("seed-" + seed_format.kind + seed_format.extension);
        if (exporter.Export(source, seed_format.format, target.string()) != AI_SUCCESS)
            throw std::runtime_error("assimp cannot export " + seed_format.format);
    }
    auto import_and_use = [&](const fs::path& p, const ImportSeed& seed_format) {
        for (const auto& entry : fs::directory_iterator(export_dir)) // the .bin and the like
            if (entry.path().extension() == ".bin")
                fs::copy_file(entry.path(), p.parent_path() / entry.path().filename(),
                              fs::copy_options::overwrite_existing);
        const auto input = p.parent_path() / ("input" + seed_format.extension);
        fs::rename(p, input);
        rad::SceneOptions options;
        options.import.seconds = 20; // a hang is a refusal, soon
        auto s = rad::load_scene(input, options);
        rad::SubdivisionOptions o;
        o.max_edge = 0.6;
        o.max_patches = 1e5;
        use_mesh(rad::subdivide(s, o));
    };
    std::vector<Kind> kinds{
        {"mesh",
         {read_bytes(dir / "seed.mesh"), read_bytes(dir / "seed-polygon.mesh"),
          read_bytes(dir / "seed-specular.mesh")},
         false,
         [](const fs::path& p) { use_mesh(radfmt::read_mesh(p)); }},
        {"formfactors",
         {read_bytes(dir / "seed.ff")},
         false,
         [&](const fs::path& p) {
             use_form_factors(mesh_copy, radfmt::read_form_factors(p));
             // rad-solve's layout: the rows packed, decoded as the solvers read them.
             use_form_factors(mesh_copy, radfmt::read_form_factors(
                                             p, nullptr, radfmt::FormFactorLayout::compact));
         }},
        {"links",
         {read_bytes(dir / "seed.links")},
         false,
         [&](const fs::path& p) { use_links(mesh_copy, radfmt::read_links(p)); }},
        {"radiosity",
         {read_bytes(dir / "seed.rad"), read_bytes(dir / "seed-groups.rad")},
         false,
         [&](const fs::path& p) { use_radiosity(mesh_copy, radfmt::read_radiosity(p)); }},
        {"luminaires",
         {read_bytes(dir / "seed.lum")},
         false,
         [&](const fs::path& p) { use_luminaires(radfmt::read_luminaires(p)); }},
        {"sky",
         {read_bytes(dir / "seed.sky")},
         false,
         [&](const fs::path& p) { use_sky(radfmt::read_sky(p)); }},
        {"annual",
         {read_bytes(dir / "seed.ill")},
         false,
         [&](const fs::path& p) { (void)rad::annual_metrics(radfmt::read_annual(p)); }},
        {"epw", {read_bytes(epw)}, true, [&](const fs::path& p) { use_weather(p); }},
        {"calc", {Bytes(calc_seed.begin(), calc_seed.end())}, true, use_calc},
        {"spectrum", {Bytes(spectrum_seed.begin(), spectrum_seed.end())}, true, use_spectrum},
        {"ies", {read_bytes(ies)}, true, [&](const fs::path& p) { use_photometry(p, "f.ies"); }},
        {"ldt", {read_bytes(ldt)}, true, [&](const fs::path& p) { use_photometry(p, "f.ldt"); }},
        {"obj",
         {read_bytes(obj)},
         true,
         [&](const fs::path& p) {
             fs::copy_file(mtl, p.parent_path() / mtl.filename(),
                           fs::copy_options::overwrite_existing);
             auto s = rad::load_scene(p);
             rad::remove_duplicate_faces(s);
             rad::imprint_contacts(s); // rad-mesh's default path
             rad::SubdivisionOptions o;
             o.max_edge = 0.6;
             o.max_patches = 1e5;
             use_mesh(rad::subdivide(s, o));
         }},
        {"mtl",
         {read_bytes(mtl)},
         true,
         [&](const fs::path& p) {
             fs::copy_file(obj, p.parent_path() / obj.filename(),
                           fs::copy_options::overwrite_existing);
             fs::rename(p, p.parent_path() / mtl.filename());
             auto s = rad::load_scene(p.parent_path() / obj.filename());
             rad::SubdivisionOptions o;
             o.max_edge = 0.6;
             use_mesh(rad::subdivide(s, o));
         }},
    };
    for (const auto& seed_format : import_seeds)
        kinds.push_back(
            {seed_format.kind,
             {read_bytes(export_dir / ("seed-" + seed_format.kind + seed_format.extension))},
             true,
             [&, seed_format](const fs::path& p) { import_and_use(p, seed_format); }});

    int status = 0;
    for (const auto& kind : kinds) {
        if (!only.empty() && only.find("," + kind.name + ",") == std::string::npos) continue;
        Mutator mutator(seed ^ std::hash<std::string>{}(kind.name));
        Tally tally;
        const auto start = std::chrono::steady_clock::now();
        const auto work = dir / kind.name;
        long done = 0;
        for (; done < iterations; ++done) {
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
                seconds)
                break;
            Bytes bytes = kind.seeds[mutator.below(kind.seeds.size())];
            if (kind.text) {
                mutator.mutate_text(bytes);
            } else {
                auto c = split(bytes);
                const auto edits = 1 + mutator.below(3);
                for (std::size_t k = 0; k < edits; ++k) {
                    if (mutator.chance(0.2))
                        mutator.mutate_header(c.lines);
                    else
                        mutator.mutate_body(c.body);
                }
                bytes = join(std::move(c));
            }
            fs::remove_all(work);
            fs::create_directories(work);
            const auto input = work / ("input." + kind.name);
            write_bytes(input, bytes);
            std::string failure;
            if (!expected_refusal([&] { kind.read_and_use(input); }, tally, failure)) {
                const auto keep =
                    fs::path("fuzz-failure-" + kind.name + "-" + std::to_string(done));
                write_bytes(keep, bytes);
                std::cerr << "fuzz_readers: " << kind.name << " case " << done << ": " << failure
                          << " (input kept in " << keep.string() << ")\n";
                status = 1;
                break;
            }
        }
        std::cerr << "fuzz_readers: " << kind.name << ": " << done << " cases, " << tally.read
                  << " read, " << tally.refused << " refused";
        if (tally.importer_failed)
            std::cerr << " (" << tally.importer_failed << " by the importer's failure)";
        std::cerr << "\n";
        if (status == 0 && done < min_cases && done < iterations) {
            std::cerr << "fuzz_readers: " << kind.name << ": only " << done << " cases within "
                      << seconds << " s, fewer than --min-cases " << min_cases << "\n";
            status = 1;
        }
    }
    fs::remove_all(dir);
    return status;
}
