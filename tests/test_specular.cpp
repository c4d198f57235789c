// Mirrors and glass: the materials read from MTL and glTF parameters, the optics (Fresnel,
// Radiance's glass), extended form factors against closed forms, and the mesh format.
#include "formfactor/sampling.hpp"
#include "helpers.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/specular.hpp"
#include "radiosity/specular_materials.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace testing_helpers;
using radfmt::SpecularKind;

namespace {

constexpr double kPi = std::numbers::pi;

std::string v(double x, double y, double z) {
    return "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
}

double entry(const radfmt::FormFactorData& ff, std::uint32_t row, std::uint32_t col) {
    for (auto k = ff.row_start[row]; k < ff.row_start[row + 1]; ++k)
        if (ff.columns[k] == col) return ff.values[k];
    return 0;
}

radfmt::FormFactorData hemisphere(const radfmt::MeshData& mesh, int rays, int depth = 12) {
    rad::FormFactorOptions options;
    options.method = "hemisphere";
    options.rays = rays;
    options.quiet = true;
    options.specular_depth = depth;
    return rad::compute_form_factors(mesh, options);
}

// The form factor from rectangle [x1,x2] x [y1,y2] at z = 0 to the parallel rectangle
// [u1,u2] x [w1,w2] at z = c facing it: the corner sum of Howell's configuration C-11 in
// general position (an independent closed form, not the library's).
double offset_parallel(double x1, double x2, double y1, double y2, double u1, double u2, double w1,
                       double w2, double c) {
    const auto g = [c](double x, double y) {
        const double px = std::sqrt(x * x + c * c), py = std::sqrt(y * y + c * c);
        return (y * px * std::atan(y / px) + x * py * std::atan(x / py) -
                0.5 * c * c * std::log(x * x + y * y + c * c)) /
               (2 * kPi);
    };
    const double xs[2] = {x1, x2}, ys[2] = {y1, y2}, us[2] = {u1, u2}, ws[2] = {w1, w2};
    double sum = 0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k)
                for (int l = 0; l < 2; ++l) {
                    const double sign = ((i + j + k + l) % 2) ? -1 : 1;
                    sum += sign * g(xs[i] - us[k], ys[j] - ws[l]);
                }
    return sum / ((x2 - x1) * (y2 - y1));
}

rad::MtlSpecularInput mtl(int illum) {
    rad::MtlSpecularInput in;
    in.illum = illum;
    in.diffuse = {{0.1, 0.1, 0.1}};
    in.specular = {{0.8, 0.8, 0.8}};
    return in;
}

} // namespace

TEST_CASE("the independent offset closed form agrees with the aligned one") {
    CHECK(offset_parallel(0, 1, 0, 1, 0, 1, 0, 1, 1) ==
          Approx(rad::parallel_rectangles_form_factor(1, 1, 1)).epsilon(1e-9));
    CHECK(offset_parallel(0, 2, 0, 1, 0, 2, 0, 1, 0.5) ==
          Approx(rad::parallel_rectangles_form_factor(2, 1, 0.5)).epsilon(1e-9));
}

TEST_CASE("MTL illumination models become mirrors, Fresnel mirrors, panes and refracting "
          "boundaries") {
    const auto read = [](const rad::MtlSpecularInput& in) {
        return rad::read_mtl_material(in).specular;
    };
    auto mirror = read(mtl(3));
    CHECK(mirror.kind == SpecularKind::mirror);
    CHECK(mirror.reflectance[0] == 0.8);
    CHECK(read(mtl(5)).kind == SpecularKind::fresnel);
    auto glass = mtl(7);
    glass.ior = 1.33;
    glass.states_ior = true;
    glass.filter = {{0.9, 0.8, 0.7}};
    glass.states_filter = true;
    const auto water = read(glass);
    CHECK(water.kind == SpecularKind::dielectric);
    CHECK(water.ior == 1.33);
    CHECK(water.transmittance[2] == 0.7);
    glass.ior = 1; // Ni 1: glass's index
    CHECK(read(glass).ior == 1.5);
    auto pane = mtl(4);
    pane.filter = {{0.7, 0.7, 0.7}};
    pane.states_filter = true;
    CHECK(read(pane).kind == SpecularKind::pane);
    CHECK(read(pane).transmittance[0] == 0.7);
    // d < 1 with an opaque model: transparency without refraction, a pane of 1 - d whose
    // diffuse part is the covered share.
    auto dissolved = mtl(2);
    dissolved.dissolve = 0.25;
    dissolved.states_dissolve = true;
    const auto open = rad::read_mtl_material(dissolved);
    CHECK(open.specular.kind == SpecularKind::pane);
    CHECK(open.specular.transmittance[1] == Approx(0.75));
    CHECK(open.diffuse[0] == Approx(0.025));
    // Exporters write Tf 1 1 1 on every material: alone it makes nothing transmit, and a
    // Phong highlight (illum 2, Ks) is no mirror.
    auto opaque = mtl(2);
    opaque.filter = {{1, 1, 1}};
    opaque.states_filter = true;
    CHECK(read(opaque).kind == SpecularKind::none);
    // Ns as a roughness, kept.
    auto shiny = mtl(3);
    shiny.shininess = 1000;
    CHECK(read(shiny).roughness == Approx(std::sqrt(2.0 / 1002)));
}

namespace {
// A material as Maya's OBJ exporter writes every one: illum 4, Kd, Tf 1 1 1, Ni 1, Ks 0.5.
rad::MtlSpecularInput maya(const std::string& name, double kd) {
    rad::MtlSpecularInput in;
    in.name = name;
    in.illum = 4;
    in.diffuse = {{kd, kd, kd}};
    in.specular = {{0.5, 0.5, 0.5}};
    in.filter = {{1, 1, 1}};
    in.states_filter = in.states_ior = true;
    return in;
}
} // namespace

TEST_CASE("illum 4 is glass only where the file marks it see-through") {
    // Maya's floor, walls and area light: opaque, said, their Kd kept.
    for (const double kd : {0.0, 0.5, 1.0}) {
        const auto floor = rad::read_mtl_material(maya("lambert2SG", kd));
        CHECK(floor.specular.kind == SpecularKind::none);
        CHECK(floor.diffuse[0] == kd);
        CHECK(!floor.changed);
        CHECK_THAT(floor.why, Catch::StartsWith("opaque: illum 4") && Catch::Contains("Maya"));
    }
    // Tf below 1, an index, a name, d below 1: each marks glass.
    auto tinted = maya("pane", 0.05);
    tinted.filter = {{0.8, 0.8, 0.8}};
    CHECK(rad::read_mtl_material(tinted).specular.transmittance[0] == 0.8);
    auto indexed = maya("m1", 0.05);
    indexed.ior = 1.5;
    CHECK(rad::read_mtl_material(indexed).specular.kind == SpecularKind::pane);
    CHECK_THAT(rad::read_mtl_material(indexed).why, Catch::Contains("Ni 1.5 with illum 4"));
    CHECK(rad::read_mtl_material(maya("Window_Glass", 0.05)).specular.kind == SpecularKind::pane);
    CHECK(rad::read_mtl_material(maya("fensterGlas", 0.05)).specular.kind == SpecularKind::pane);
    auto faded = maya("m2", 0.5);
    faded.dissolve = 0.4;
    faded.states_dissolve = true;
    CHECK(rad::read_mtl_material(faded).specular.transmittance[0] == Approx(0.6));
    // Tf 0 transmits nothing, whatever else says glass.
    auto black = maya("glass", 0.5);
    black.filter = {};
    black.ior = 1.8;
    const auto shut = rad::read_mtl_material(black);
    CHECK(shut.specular.kind == SpecularKind::none);
    CHECK_THAT(shut.why, Catch::Contains("Tf 0 transmits nothing"));
    // Named like glass, illum 2, d 1: opaque, and said how to make it glass.
    auto named = maya("Glass", 0.2);
    named.illum = 2;
    CHECK(rad::read_mtl_material(named).specular.kind == SpecularKind::none);
    CHECK_THAT(rad::read_mtl_material(named).why, Catch::Contains("--transmittance"));
    // A plain material says nothing.
    auto plain = maya("wall", 0.5);
    plain.illum = 2;
    CHECK(rad::read_mtl_material(plain).why.empty());
}

TEST_CASE("MTL values out of range are clamped and shares over 1 scaled, each said") {
    // 3ds Max's Max2Obj window: illum 2, d 0.5, Kd 0.6 0.7 0.8 (refused before as 1.15 x
    // the light it gets): a pane of 0.5 whose covered half reflects Kd.
    rad::MtlSpecularInput window;
    window.name = "Windows";
    window.illum = 2;
    window.diffuse = {{0.6, 0.7, 0.8}};
    window.specular = {{0.9, 0.9, 0.9}};
    window.dissolve = 0.5;
    window.states_dissolve = true;
    const auto pane = rad::read_mtl_material(window);
    CHECK(pane.specular.kind == SpecularKind::pane);
    CHECK(pane.specular.transmittance[0] == Approx(0.5));
    CHECK(pane.diffuse[2] == Approx(0.4));
    CHECK(!pane.changed);
    // A glass whose Kd leaves no room: Kd lowered (one factor, the colour kept), said.
    auto crowded = maya("glass", 0.6);
    crowded.diffuse = {{0.6, 0.3, 0.6}};
    crowded.filter = {{0.7, 0.7, 0.7}};
    const auto fitted = rad::read_mtl_material(crowded);
    CHECK(fitted.changed);
    CHECK_THAT(fitted.why, Catch::Contains("Kd scaled"));
    radfmt::Material m{"glass", fitted.diffuse, {}, fitted.specular};
    CHECK(rad::fit_specular_energy(m).empty()); // holds now
    CHECK(fitted.diffuse[1] / fitted.diffuse[0] == Approx(0.5));
    const auto shares = rad::pane_shares(rad::pane_transmissivity(0.7, 1.52), 1.52, 1);
    CHECK(fitted.diffuse[0] + shares.reflected + shares.transmitted == Approx(1));
    // A mirror with Kd 0.8 and Ks 0.5 (Blender's metals): both scaled to add up to 1.
    auto metal = mtl(3);
    metal.diffuse = {{0.8, 0.8, 0.8}};
    metal.specular = {{0.5, 0.5, 0.5}};
    const auto scaled = rad::read_mtl_material(metal);
    CHECK(scaled.diffuse[0] + scaled.specular.reflectance[0] == Approx(1));
    CHECK(scaled.specular.reflectance[0] / scaled.diffuse[0] == Approx(0.5 / 0.8));
    // Ks 1.5, Tf 3, d -1 and Ni 0 brought into range, each said.
    auto wild = mtl(4);
    wild.name = "wild";
    wild.specular = {{1.5, 1.5, 1.5}};
    wild.filter = {{3, 0.5, 0.5}};
    wild.states_filter = true;
    wild.ior = 0;
    wild.states_ior = true;
    const auto tamed = rad::read_mtl_material(wild);
    CHECK(tamed.changed);
    CHECK(tamed.specular.transmittance[0] == 1);
    CHECK(tamed.specular.ior == Approx(rad::kPaneIndex));
    CHECK_THAT(tamed.why, Catch::Contains("Tf 3,0.5,0.5 clamped to 1") &&
                              Catch::Contains("Ni 0 is no glass's index"));
    // Ks is said where a mirror uses it, not on glass or a diffuse material that ignores it.
    CHECK_THAT(tamed.why, !Catch::Contains("Ks"));
    auto bright = mtl(3);
    bright.specular = {{1.5, 1.5, 1.5}};
    bright.diffuse = {};
    CHECK_THAT(rad::read_mtl_material(bright).why, Catch::Contains("Ks 1.5,1.5,1.5 clamped to 1"));
    bright.illum = 2;
    CHECK(rad::read_mtl_material(bright).why.empty());
    wild.dissolve = std::nan("");
    wild.states_dissolve = true;
    CHECK_THAT(rad::read_mtl_material(wild).why, Catch::Contains("d nan taken as 1"));
}

TEST_CASE("glTF metallic-roughness, transmission, ior and volume") {
    rad::PbrSpecularInput in;
    in.base = {{0.9, 0.9, 0.9}};
    in.metallic = 1;
    in.roughness = 0.05;
    radfmt::Rgb diffuse;
    auto s = rad::specular_from_pbr(in, diffuse);
    CHECK(s.kind == SpecularKind::fresnel);
    CHECK(s.reflectance[0] == Approx(0.9));
    CHECK(diffuse[0] == Approx(0));
    in.roughness = 1; // glTF's default: a rough metal stays diffuse
    CHECK(rad::specular_from_pbr(in, diffuse).kind == SpecularKind::none);
    CHECK(diffuse[0] == Approx(0.9));
    in.metallic = 0;
    in.transmission = 1;
    in.ior = 1.4;
    s = rad::specular_from_pbr(in, diffuse);
    CHECK(s.kind == SpecularKind::pane); // thin-walled without a volume
    CHECK(s.ior == 1.4);
    CHECK(diffuse[0] == Approx(0));
    in.thickness = 0.1;
    CHECK(rad::specular_from_pbr(in, diffuse).kind == SpecularKind::dielectric);
}

TEST_CASE("Fresnel: 4% at normal incidence for glass, total internal reflection, energy") {
    CHECK(rad::fresnel_reflectance(1, 1, 1.5) == Approx(0.04));
    CHECK(rad::fresnel_reflectance(0.1, 1.5, 1) == 1); // past the critical angle
    // The same boundary from either side at Snell's pair of angles reflects the same.
    const double ci = 0.8, si = std::sqrt(1 - ci * ci), ct = std::sqrt(1 - si * si / 2.25);
    CHECK(rad::fresnel_reflectance(ci, 1, 1.5) == Approx(rad::fresnel_reflectance(ct, 1.5, 1)));
}

TEST_CASE("Radiance's glass: a clear pane of 0.88, and the transmissivity inverts the pane") {
    // Radiance: transmissivity from transmittance tn at n = 1.52.
    const double tn = 0.88;
    const double radiance =
        (std::sqrt(0.8402528435 + 0.0072522239 * tn * tn) - 0.9166530661) / 0.0036261119 / tn;
    CHECK(rad::pane_transmissivity(tn, 1.52) == Approx(radiance).epsilon(1e-6));
    for (const double t : {0.1, 0.5, 0.7, 0.9}) {
        const double trans = rad::pane_transmissivity(t, 1.52);
        CHECK(rad::pane_shares(trans, 1.52, 1).transmitted == Approx(t).epsilon(1e-9));
        const auto grazing = rad::pane_shares(trans, 1.52, 0.2);
        CHECK(grazing.transmitted < t);
        CHECK(grazing.transmitted + grazing.reflected <= 1);
    }
}

TEST_CASE("two squares between two parallel mirrors: the lattice sum of their images", "[slow]") {
    // A at z = 0 facing up and B at z = d facing down fill [0,1]^2; mirror walls at x = 0 and
    // x = 1 close the gap between them (y's sides open). Unfolded, B repeats at x offsets k,
    // seen after |k| reflections.
    const double d = 0.7, rho = 0.8;
    const std::string mtl = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl mirror\nillum 3\nKd 0 0 0\n"
                            "Ks 0.8 0.8 0.8\n";
    std::string obj = v(0, 0, 0) + v(1, 0, 0) + v(1, 1, 0) + v(0, 1, 0) + v(0, 0, d) + v(1, 0, d) +
                      v(1, 1, d) + v(0, 1, d);
    obj += "usemtl white\nf 1 2 3 4\nf 5 8 7 6\nusemtl mirror\nf 1 4 8 5\nf 2 6 7 3\n";
    const auto mesh = rad::subdivide(scene_from_obj(obj, mtl), {});
    REQUIRE(mesh.patches.size() == 4);
    REQUIRE(mesh.has_specular());
    double lattice = 0;
    for (int k = -40; k <= 40; ++k)
        lattice += std::pow(rho, std::abs(k)) * offset_parallel(0, 1, 0, 1, k, k + 1, 0, 1, d);
    const auto ff = hemisphere(mesh, 1 << 20, 64);
    CHECK(entry(ff, 0, 1) == Approx(lattice).epsilon(0.005));
    CHECK(entry(ff, 1, 0) == Approx(lattice).epsilon(0.005));
    // Without the mirrors' specular part, only the direct view.
    auto plain = mesh;
    for (auto& m : plain.materials) m.specular = {};
    CHECK(entry(hemisphere(plain, 1 << 18), 0, 1) ==
          Approx(rad::parallel_rectangles_form_factor(1, 1, d)).epsilon(0.01));
}

TEST_CASE("a patch facing a parallel mirror sees its own image: rho F(2h)", "[slow]") {
    const double h = 0.4;
    const std::string mtl = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl mirror\nillum 3\nKd 0 0 0\n"
                            "Ks 0.9 0.9 0.9\n";
    const std::string obj = v(0, 0, 0) + v(1, 0, 0) + v(1, 1, 0) + v(0, 1, 0) + v(0, 0, h) +
                            v(1, 0, h) + v(1, 1, h) + v(0, 1, h) +
                            "usemtl white\nf 1 2 3 4\nusemtl mirror\nf 5 8 7 6\n";
    const auto mesh = rad::subdivide(scene_from_obj(obj, mtl), {});
    REQUIRE(mesh.patches.size() == 2);
    const auto ff = hemisphere(mesh, 1 << 20);
    CHECK(entry(ff, 0, 0) ==
          Approx(0.9 * rad::parallel_rectangles_form_factor(1, 1, 2 * h)).epsilon(0.005));
    // The hemi-cube's pixel rays go on at the mirror the same way.
    rad::FormFactorOptions cube;
    cube.method = "hemicube";
    cube.resolution = 512;
    cube.quiet = true;
    CHECK(entry(rad::compute_form_factors(mesh, cube), 0, 0) ==
          Approx(0.9 * rad::parallel_rectangles_form_factor(1, 1, 2 * h)).epsilon(0.005));
    // The mirror's own (diffuse) part is seen directly, unweighted.
    CHECK(entry(ff, 0, 1) == Approx(rad::parallel_rectangles_form_factor(1, 1, h)).epsilon(0.005));
}

TEST_CASE("a pane between emitter and receiver passes the glass model's angular share", "[slow]") {
    // Receiver at z = 0 facing up, a wide pane (normal transmittance 0.7) at z = 0.5, the
    // emitter's square at z = 1 facing down.
    const double tn = 0.7, ior = 1.52;
    const std::string mtl = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl glass\nillum 4\nKd 0 0 0\n"
                            "Tf 0.7 0.7 0.7\nNi 1.52\n";
    const std::string obj = v(0, 0, 0) + v(1, 0, 0) + v(1, 1, 0) + v(0, 1, 0) + v(0, 0, 1) +
                            v(1, 0, 1) + v(1, 1, 1) + v(0, 1, 1) + v(-3, -3, 0.5) + v(4, -3, 0.5) +
                            v(4, 4, 0.5) + v(-3, 4, 0.5) +
                            "usemtl white\nf 1 2 3 4\nf 5 8 7 6\nusemtl glass\nf 9 10 11 12\n";
    const auto mesh = rad::subdivide(scene_from_obj(obj, mtl), {});
    REQUIRE(mesh.patches.size() == 3);
    REQUIRE(mesh.materials[mesh.patches[2].material].specular.kind == SpecularKind::pane);
    // The reference: the form factor's double integral with the pane's transmittance at each
    // pair's angle, by Gauss-Legendre quadrature (no rays).
    const double t = rad::pane_transmissivity(tn, ior);
    const int m = 14;
    // The analytic method's Gauss-Legendre rule; its sum without the pane is checked below
    // against the closed form, so the rule vouches for itself.
    std::vector<double> x, w;
    rad::ff::gauss_legendre(m, x, w);
    double plain = 0, through = 0;
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b)
            for (int c = 0; c < m; ++c)
                for (int e = 0; e < m; ++e) {
                    const double dx = x[a] - x[c], dy = x[b] - x[e];
                    const double r2 = dx * dx + dy * dy + 1;
                    const double kernel = w[a] * w[b] * w[c] * w[e] / (kPi * r2 * r2);
                    plain += kernel;
                    through += kernel * rad::pane_shares(t, ior, 1 / std::sqrt(r2)).transmitted;
                }
    REQUIRE(plain == Approx(rad::parallel_rectangles_form_factor(1, 1, 1)).epsilon(1e-4));
    const auto ff = hemisphere(mesh, 1 << 20);
    CHECK(entry(ff, 0, 1) == Approx(through).epsilon(0.01));
    CHECK(through / plain < tn); // oblique rays lose more than normal ones
}

TEST_CASE("mesh version 3 keeps the specular parts; a mesh without keeps version and hash") {
    const std::string mtl = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl mirror\nillum 3\nKd 0 0 0\n"
                            "Ks 0.9 0.9 0.9\nNs 200\n";
    const std::string obj = v(0, 0, 0) + v(1, 0, 0) + v(1, 1, 0) + v(0, 1, 0) + v(0, 0, 1) +
                            v(1, 0, 1) + v(1, 1, 1) + v(0, 1, 1) +
                            "usemtl white\nf 1 2 3 4\nusemtl mirror\nf 5 8 7 6\n";
    auto mesh = rad::subdivide(scene_from_obj(obj, mtl), {});
    const auto dir = temp_dir("specular-mesh");
    radfmt::Header header;
    header.tool = "test";
    radfmt::write_mesh(dir / "m.mesh", header, mesh);
    radfmt::Header read_header;
    const auto back = radfmt::read_mesh(dir / "m.mesh", &read_header);
    CHECK(read_header.version == 3);
    for (std::size_t k = 0; k < mesh.materials.size(); ++k)
        CHECK(back.materials[k].specular == mesh.materials[k].specular);
    CHECK(back.geometry_hash() == mesh.geometry_hash());
    // The specular parts are in the geometry hash: a .ff for one mirror is not another's.
    const auto with_mirror = mesh.geometry_hash();
    auto duller = mesh;
    for (auto& m : duller.materials)
        if (m.specular.any()) m.specular.reflectance = {{0.5, 0.5, 0.5}};
    CHECK(duller.geometry_hash() != with_mirror);
    // A diffuse change is not.
    auto repainted = mesh;
    repainted.materials[0].reflectance = {{0.2, 0.2, 0.2}};
    CHECK(repainted.geometry_hash() == with_mirror);
    // Without specular parts: the hash of the geometry alone, and version 1 as before.
    auto plain = mesh;
    for (auto& m : plain.materials) m.specular = {};
    radfmt::write_mesh(dir / "p.mesh", header, plain);
    radfmt::read_mesh(dir / "p.mesh", &read_header);
    CHECK(read_header.version == 1);
    CHECK(plain.geometry_hash() != with_mirror);
    auto unused = plain; // a specular material no patch uses changes nothing
    unused.materials.push_back(mesh.materials[1]);
    unused.materials.back().name = "spare";
    CHECK(unused.geometry_hash() == plain.geometry_hash());
    fs::remove_all(dir);
}

TEST_CASE("a sensor behind a pane gets the light the glass transmits", "[slow]") {
    // The lamp (1 x 1, 10 W/m^2, facing down at z = 1) over a sensor at (0.5, 0.5, 0) facing
    // up, a wide pane of 0.7 at z = 0.5 between them: the irradiance is the lamp's form factor
    // weighted by the pane's transmittance at each direction (2D quadrature over the lamp).
    const double tn = 0.7, ior = 1.52, e = 10;
    const std::string mtl = "newmtl lamp\nKd 0 0 0\nKe 10 10 10\nnewmtl glass\nillum 4\nKd 0 0 0\n"
                            "Tf 0.7 0.7 0.7\nNi 1.52\n";
    const std::string obj = v(0, 0, 1) + v(1, 0, 1) + v(1, 1, 1) + v(0, 1, 1) + v(-3, -3, 0.5) +
                            v(4, -3, 0.5) + v(4, 4, 0.5) + v(-3, 4, 0.5) +
                            "usemtl lamp\nf 1 4 3 2\nusemtl glass\nf 5 6 7 8\n";
    const auto mesh = rad::subdivide(scene_from_obj(obj, mtl), {});
    REQUIRE(mesh.patches.size() == 2);
    std::vector<radfmt::Rgb> b(2);
    b[0] = {{e, e, e}};
    const double t = rad::pane_transmissivity(tn, ior);
    const int m = 64;
    double expected = 0, open = 0;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) { // midpoints over the lamp
            const double dx = (i + 0.5) / m - 0.5, dy = (j + 0.5) / m - 0.5;
            const double r2 = dx * dx + dy * dy + 1;
            const double kernel = 1 / (kPi * r2 * r2) / (m * m); // cos cos / (pi r^2) dA
            open += kernel;
            expected += kernel * rad::pane_shares(t, ior, 1 / std::sqrt(r2)).transmitted;
        }
    // At the defaults: the direct sampling's shadow rays go on through the pane with its
    // transmission at their angle (before, the glass blocked them and 65536 indirect rays
    // found the lamp within 2%); the indirect rays through it take nothing of the lamp twice.
    const rad::Gatherer gatherer(mesh, b, rad::GatherOptions{});
    const auto got = gatherer.gather({0.5, 0.5, 0}, {0, 0, 1}, 3);
    CHECK(got.direct[0] == Approx(e * expected).epsilon(0.005));
    CHECK(got.indirect[0] == 0);
    CHECK(expected < tn * open);
}
