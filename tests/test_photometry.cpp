// Photometric files: every public fixture read and integrated, malformed files refused with
// FILE:LINE, interpolation and symmetry against values worked out by hand.
#include "radiosity/gather.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/melanopic.hpp"
#include "radiosity/photometry.hpp"
#include "radiosity/rays.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

using Catch::Detail::Approx;
namespace fs = std::filesystem;

namespace {
const fs::path kData = fs::path(RADIOSITY_SOURCE_DIR) / "tests/data/photometry";

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

rad::Photometry read(const std::string& file) {
    return rad::parse_photometry(slurp(kData / file), file, nullptr);
}

// The message of the InputError `text` gives, or "" when it is read.
std::string refusal(const std::string& text, const std::string& name = "bad.ies") {
    try {
        rad::parse_photometry(text, name, nullptr);
    } catch (const rad::InputError& e) {
        return e.what();
    }
    return "";
}
} // namespace

TEST_CASE("EULUMDAT's lamp colour temperature and colour rendering are read as stated") {
    const auto uplight = read("eulumdat-rs_floor_uplight_Isym0.ldt"); // "nw/4200", "1B/86"
    CHECK(uplight.cct == 4200);
    CHECK(uplight.colour_rendering == "1B/86");
    const auto projector = read("eulumdat-rs_projector_Isym2.ldt"); // "ww/3000", empty
    CHECK(projector.cct == 3000);
    CHECK(projector.colour_rendering.empty());
    const auto sample = read("eulumdat-ugr_sample_01_Isym4.ldt"); // "0", "0": not stated
    CHECK(sample.cct == 0);
    CHECK(sample.colour_rendering.empty());
}

TEST_CASE("EULUMDAT's company, luminaire name and number are kept as the IES keywords") {
    // The report names a luminaire by LUMINAIRE (before: the file's name for every LDT).
    const auto sample = read("eulumdat-ugr_sample_01_Isym4.ldt"); // lines 1, 9, 10
    const auto value = [&](const std::string& key) {
        for (const auto& [k, v] : sample.keywords)
            if (k == key) return v;
        return std::string("(none)");
    };
    CHECK(value("MANUFAC") == "company");
    CHECK(value("LUMINAIRE") == "sample_01");
    CHECK(value("LUMCAT") == "sample_01");
}

TEST_CASE("every public photometric fixture reads and integrates to its stated flux") {
    struct Expect {
        const char* file;
        rad::PhotometricType type;
        double flux;      // lm the file states or implies; 0: not stated (absolute)
        double tolerance; // relative
    };
    // EULUMDAT states lamps x LORL; relative IES files their lamp lumens, which bound the
    // integral (their LOR, not given in the file, is the ratio).
    const Expect fixtures[] = {
        {"eulumdat-rs_floor_uplight_Isym0.ldt", rad::PhotometricType::C, 20000 * 0.7233, 0.02},
        {"eulumdat-ugr_sample_09_Isym1.ldt", rad::PhotometricType::C, 13729 * 1.00, 0.02},
        // Its intensities integrate to 2.1% over its LORL (checked by a brute-force sum): warned.
        {"eulumdat-rs_projector_Isym2.ldt", rad::PhotometricType::C, 6500 * 0.7771, 0.025},
        {"eulumdat-rs_road_luminaire_Isym3.ldt", rad::PhotometricType::C, 33200 * 0.8442, 0.02},
        {"eulumdat-ugr_sample_01_Isym4.ldt", rad::PhotometricType::C, 12334 * 1.00, 0.02},
    };
    for (const auto& f : fixtures) {
        INFO(f.file);
        const auto p = read(f.file);
        CHECK(p.type == f.type);
        CHECK(p.flux() == Approx(f.flux).epsilon(f.tolerance));
        CHECK(rad::flux_warnings(p).empty() ==
              (std::string(f.file) != "eulumdat-rs_projector_Isym2.ldt"));
    }
    for (const char* file :
         {"luxcore_ASA_15M_R2.ies", "photon-v2_ERCO_Panarc_corridor_1.ies",
          "photon-v2_Lithonia_KBD8_bollard_9.IES", "photon-v2_Halo_L1768_wallwasher.ies",
          "eulumdat-rs_TILT_TEST_SYNTHETIC.ies", "eulumdat-rs_ABSOLUTE_LED.ies",
          "appleseed_test_iesparser_2_typeB_ACP.ies", "photompy_tilt_include_v19.ies",
          "threejs_BEGA_84659K4_h90-270.ies"}) {
        INFO(file);
        const auto p = read(file);
        const double flux = p.flux();
        CHECK(flux > 0);
        // The synthetic TILT file's intensities make 323% of its lamp: warned, as it should be.
        const bool synthetic = std::string(file) == "eulumdat-rs_TILT_TEST_SYNTHETIC.ies";
        CHECK(rad::flux_warnings(p).empty() == !synthetic);
        if (p.lamp_lumens > 0 && !synthetic) CHECK(flux <= 1.02 * p.lamp_lumens);
    }
    // The BEGA file is absolute; its label says 9600 lm: the 90-270 layout mirrored right.
    CHECK(read("threejs_BEGA_84659K4_h90-270.ies").flux() == Approx(9600).epsilon(0.001));
    // Editions and systems as the files say.
    CHECK(read("photompy_tilt_include_v19.ies").edition == "LM-63-2019");
    CHECK(read("photon-v2_Lithonia_KBD8_bollard_9.IES").edition == "LM-63-1991");
    CHECK(read("appleseed_test_iesparser_2_typeB_ACP.ies").type == rad::PhotometricType::B);
    const auto tilted = read("eulumdat-rs_TILT_TEST_SYNTHETIC.ies");
    REQUIRE(tilted.tilt.angles.size() == 4);
    CHECK(tilted.tilt.factor(45) == Approx(0.9));
    CHECK(tilted.tilt.factor(67.5) == Approx(0.85));
    CHECK(tilted.tilt.factor(135) == Approx(0.9));
}

namespace {
// I = 1000 cos(gamma) on gamma 0-90 at 1 degree, one plane, its opening "WIDTH LENGTH" (metres).
std::string cosine_ies(const std::string& opening) {
    std::string text = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 91 1 1 2 " + opening + " 0\n1 1 0\n";
    for (int g = 0; g <= 90; ++g) text += std::to_string(g) + " ";
    text += "\n0\n";
    char value[32];
    for (int g = 0; g <= 90; ++g) {
        std::snprintf(value, sizeof value, "%.6f ", 1000 * std::cos(g * std::numbers::pi / 180));
        text += value;
    }
    return text;
}

// A small valid IES file: type C, 3 vertical angles, 2 planes 0 and 90 (quadrant symmetric).
std::string small_ies(const std::string& numbers =
                          "1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100 "
                          "60 5\n",
                      const std::string& tilt = "TILT=NONE\n") {
    return "IESNA:LM-63-2002\n[TEST] unit\n" + tilt + numbers;
}
} // namespace

TEST_CASE("interpolation is bilinear in the angles and symmetric parts are mirrored") {
    const auto p = rad::parse_ies(small_ies(), "q.ies", nullptr);
    CHECK(p.intensity(0, 0) == Approx(100));
    CHECK(p.intensity(0, 22.5) == Approx(90));
    CHECK(p.intensity(90, 45) == Approx(60));
    CHECK(p.intensity(45, 45) == Approx(70));  // halfway between the planes
    CHECK(p.intensity(180, 45) == Approx(80)); // 0-90 mirrored: C180 is C0
    CHECK(p.intensity(270, 45) == Approx(60));
    CHECK(p.intensity(315, 45) == Approx(70));
    CHECK(p.intensity(0, 120) == 0); // past the last vertical angle
    CHECK(p.length == Approx(0.1));  // metres (units 2)
    // Feet (units 1): the roadway luminaire's 1.24 ft opening.
    CHECK(read("luxcore_ASA_15M_R2.ies").length == Approx(1.24 * 0.3048));
    // A negative width is round: the ERCO luminaire's 0.262 m disc.
    const auto erco = read("photon-v2_ERCO_Panarc_corridor_1.ies");
    CHECK(erco.round);
    CHECK(erco.length == Approx(0.262));
}

TEST_CASE("a cosine distribution integrates to pi times its peak") {
    // I = 1000 cos(gamma) on gamma 0-90 at 1 degree, one plane.
    const auto p = rad::parse_ies(cosine_ies("0 0"), "cos.ies", nullptr);
    CHECK(p.flux() == Approx(1000 * std::numbers::pi).epsilon(1e-4));
    CHECK(p.downward_flux() == Approx(p.flux()));
}

TEST_CASE("malformed photometric files are refused with FILE:LINE and what is wrong") {
    struct Bad {
        std::string name, text, says;
    };
    const std::string ldt = slurp(kData / "eulumdat-ugr_sample_09_Isym1.ldt");
    const auto ldt_with = [&](int line, const std::string& value) {
        std::stringstream in(ldt);
        std::string out, l;
        for (int n = 1; std::getline(in, l); ++n) out += (n == line ? value : l) + "\n";
        return out;
    };
    const Bad cases[] = {
        {"mdl.ies", slurp(kData / "MALFORMED_mdl-sdk_test_file_format_error.ies"),
         "mdl.ies:3: expected the number of lamps, found 'file'"},
        {"notilt.ies", "IESNA:LM-63-2002\n[TEST] x\n1 1000 1 3 2 1 2 0 0 0\n",
         "notilt.ies:3: no TILT= line"},
        {"short.ies",
         small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100\n"),
         "short.ies:9: the file ends where candela value 5 of 6 should be"},
        {"long.ies",
         small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100 60 5 7\n"),
         "long.ies:9: numbers left over"},
        {"order.ies",
         small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 90 45\n0 90\n100 80 10\n100 60 5\n"),
         "order.ies:6: vertical angles must increase"},
        {"neg.ies",
         small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 -80 10\n100 60 5\n"),
         "neg.ies:8: a negative candela value"},
        {"layout.ies",
         small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 45\n100 80 10\n100 60 5\n"),
         "layout.ies:7: horizontal angles from 0.000000 to 45.000000"},
        {"type.ies",
         small_ies("1 1000 1 3 2 4 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100 60 5\n"),
         "type.ies:4: the photometric type (1 = C, 2 = B, 3 = A) must be a whole number from 1 to "
         "3"},
        {"lumens.ies",
         small_ies("1 0 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100 60 5\n"),
         "lumens.ies:4: lumens per lamp must be positive, or -1"},
        {"tiltshort.ies", small_ies("", "TILT=INCLUDE\n1\n3\n0 45 90\n1 0.9\n"),
         "tiltshort.ies:7: the file ends where a TILT multiplier should be"},
        {"empty.ies", "", "empty.ies: empty file"},
        {"isym.ldt", ldt_with(3, "5"), "isym.ldt:3: Isym (the symmetry, 0 to 4) must be"},
        {"mc.ldt", ldt_with(4, "many"),
         "mc.ldt:4: expected Mc (the number of C-planes), found 'many'"},
        {"negative.ldt", ldt_with(110, "-3"), "negative.ldt:110: a negative intensity"},
        {"cut.ldt", ldt.substr(0, ldt.size() / 2), "cut.ldt:"},
        {"truncated.ldt", "\n1\n1\n", "truncated.ldt:3: the file ends where line 4"},
        // Overflow is not light (#70 item 5): a multiplier or candela that makes more than
        // 1e12 cd, or infinity, is refused at its value, as is a TILT factor of 1e308.
        {"mult.ies",
         small_ies("1 1000 1e300 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100 60 5\n"),
         "mult.ies:8: an intensity of 100 times the file's multipliers 1e+300 is 1e+302 cd"},
        {"huge.ies",
         small_ies("1 1000 1e10 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n1e300 80 10\n100 60 5\n"),
         "huge.ies:8: an intensity of 1e+300 times the file's multipliers 1e+10 is inf cd"},
        {"max.ies",
         small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n1.7e308 80 10\n100 60 5\n"),
         "max.ies:8: an intensity of 1.7e+308 times"},
        {"tiltbig.ies", small_ies("", "TILT=INCLUDE\n1\n2\n0 90\n1 1e308\n"),
         "tiltbig.ies:7: a TILT multiplier of 1e+308"},
        {"flux.ldt", ldt_with(29, "1e306"),
         "flux.ldt:104: an intensity of 226.6 times the file's multipliers 1e+303"},
    };
    for (const auto& c : cases) {
        INFO(c.name);
        const auto message = refusal(c.text, c.name);
        CHECK(message.rfind(c.says, 0) == 0);
        if (message.rfind(c.says, 0) != 0) WARN(message);
    }
    // A TILT file is read through the reader the caller gives (the scene's folder boundary
    // is the caller's): without one, refused with the line that names it.
    CHECK(refusal(small_ies("", "TILT=lamp.tlt\n"), "t.ies")
              .rfind("t.ies:3: TILT=lamp.tlt names a file", 0) == 0);
    const auto with_file = rad::parse_ies(
        small_ies("1 1000 1 3 2 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0 90\n100 80 10\n100 60 5\n",
                  "TILT=lamp.tlt\n"),
        "t.ies", [](const std::string& name, const rad::FileLoc&) {
            CHECK(name == "lamp.tlt");
            return std::string("1\n2\n0 90\n1 0.5\n");
        });
    CHECK(with_file.tilt.factor(45) == Approx(0.75));
}

TEST_CASE("a colour temperature's tint keeps the luminance and warms or cools the light") {
    for (const double k : {2700.0, 4000.0, 6500.0}) {
        const auto t = rad::cct_tint(k);
        CHECK(0.265 * t[0] + 0.670 * t[1] + 0.065 * t[2] == Approx(1));
    }
    CHECK(rad::cct_tint(2700)[0] > rad::cct_tint(2700)[2]); // warm: more red than blue
    CHECK(rad::cct_tint(10000)[2] > rad::cct_tint(10000)[0]);
    // Radiance's white is equal energy (about 5455 K on the locus): near grey.
    const auto e = rad::cct_tint(5455);
    CHECK(e[0] == Approx(1).epsilon(0.05));
    CHECK(e[2] == Approx(1).epsilon(0.08));
    CHECK_THROWS_AS(rad::cct_tint(500), rad::InputError);
}

// ---- luminaires placed in a scene ----

namespace {
const std::string kIsotropic =
    "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 180\n0\n1000 1000\n";

// A black square of side 2 s in the plane y = 0, facing up.
radfmt::MeshData floor_mesh(double s) {
    radfmt::MeshData m;
    m.vertices = {{-s, 0, -s}, {-s, 0, s}, {s, 0, s}, {s, 0, -s}};
    radfmt::Patch p;
    p.corners = {0, 1, 2, 3};
    p.area = 4 * s * s;
    p.centroid = {0, 0, 0};
    p.normal = {0, 1, 0};
    m.patches.push_back(p);
    m.groups = {"floor"};
    m.materials = {{"black", {}, {}, {}}};
    return m;
}

rad::LuminaireSet one_luminaire(const std::string& photometry, const std::string& row,
                                const std::string& file = "lamp.ies", double unit = 1) {
    rad::LuminaireSources sources{
        "layout.csv",
        "name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group\n" + row + "\n",
        {{file, photometry}}};
    return rad::build_luminaires(sources, unit);
}
} // namespace

TEST_CASE("an isotropic point source over a plane gives I cos^3 / h^2 (inverse-square law)") {
    const auto mesh = floor_mesh(10);
    const rad::RayScene scene(mesh);
    for (const double unit : {1.0, 0.001}) { // metres, and the same scene drawn in millimetres
        const double h = 2 / unit;
        const auto set =
            one_luminaire(kIsotropic, "L,lamp.ies,0," + std::to_string(h) + ",0", "lamp.ies", unit);
        const auto& l = set.luminaires[0];
        for (int i = -4; i <= 4; ++i)
            for (int k = -4; k <= 4; ++k) {
                const rad::Vec3 p{i * 0.5 / unit, 0, k * 0.7 / unit};
                const double r = std::sqrt(p[0] * p[0] + p[2] * p[2]) * unit;
                const double cos_t = 2 / std::sqrt(4 + r * r);
                const double expect = 1000 * cos_t * cos_t * cos_t / 4;
                CHECK(rad::luminaire_illuminance(set, l, p, {0, 1, 0}, &scene) ==
                      Approx(expect).epsilon(1e-3));
            }
        CHECK(set.flux(l) == Approx(4000 * std::numbers::pi).epsilon(1e-6));
    }
}

TEST_CASE("the patch mean of a point source's light is its solid angle times the intensity") {
    // A 2 x 2 m floor under an isotropic 1000 cd source 1 m up: mean E = I Omega / A, Omega the
    // square's solid angle (4 asin(a^2 / (a^2 + h^2)) for half-side a and height h = 2 pi / 3).
    const auto mesh = floor_mesh(1);
    const rad::RayScene scene(mesh);
    const auto set = one_luminaire(kIsotropic, "L,lamp.ies,0,1,0");
    const auto e = rad::patch_direct_light(mesh, set, scene, 0, 1);
    const double omega = 4 * std::asin(1.0 / 2);
    CHECK(rad::lux(e[0]) == Approx(1000 * omega / 4).epsilon(1e-9));
}

TEST_CASE("aim and spin turn the distribution as LM-63 says; TILT dims by its table") {
    // The linear luminaire: C0 and C90 differ by up to 47% of the peak.
    const auto ldt = slurp(kData / "eulumdat-ugr_sample_01_Isym4.ldt");
    const auto p = rad::parse_ldt(ldt, "lin.ldt");
    const double g = 40 * std::numbers::pi / 180;
    const rad::Vec3 towards_x{std::sin(g), -std::cos(g), 0},
        towards_minus_z{0, -std::cos(g), -std::sin(g)};
    const auto straight = one_luminaire(ldt, "L,lin.ldt,0,3,0", "lin.ldt");
    const auto spun = one_luminaire(ldt, "L,lin.ldt,0,3,0,,,,90", "lin.ldt");
    REQUIRE(std::abs(p.intensity(0, 40) - p.intensity(90, 40)) > 0.1 * p.intensity(0, 40));
    // Aim down, spin 0: C0 along +X, C90 along -Z.
    CHECK(straight.intensity(straight.luminaires[0], towards_x) == Approx(p.intensity(0, 40)));
    CHECK(straight.intensity(straight.luminaires[0], towards_minus_z) ==
          Approx(p.intensity(90, 40)));
    // Spin 90 puts C0 where C90 was: the footprint's axes swap.
    CHECK(spun.intensity(spun.luminaires[0], towards_minus_z) == Approx(p.intensity(0, 40)));
    const auto mesh = floor_mesh(10);
    const rad::RayScene scene(mesh);
    const double e_x =
        rad::luminaire_illuminance(straight, straight.luminaires[0], {2, 0, 0}, {0, 1, 0}, &scene);
    const double e_z =
        rad::luminaire_illuminance(straight, straight.luminaires[0], {0, 0, -2}, {0, 1, 0}, &scene);
    CHECK(rad::luminaire_illuminance(spun, spun.luminaires[0], {0, 0, -2}, {0, 1, 0}, &scene) ==
          Approx(e_x));
    CHECK(rad::luminaire_illuminance(spun, spun.luminaires[0], {-2, 0, 0}, {0, 1, 0}, &scene) ==
          Approx(e_z));
    // Aimed straight up: 180 degrees about +X, so gamma 0 points up and C0 stays along +X.
    const auto up = one_luminaire(ldt, "L,lin.ldt,0,0,0,0,1,0", "lin.ldt");
    CHECK(up.luminaires[0].c0[0] == Approx(1));
    CHECK(up.luminaires[0].c90[2] == Approx(1)); // -Z turned to +Z
    // TILT: the synthetic file's table says 0.9 at 45 degrees, 0.8 at 90.
    const auto tilt = slurp(kData / "eulumdat-rs_TILT_TEST_SYNTHETIC.ies");
    const auto level = one_luminaire(tilt, "L,t.ies,0,3,0", "t.ies");
    const auto tilted = one_luminaire(tilt, "L,t.ies,0,3,0,1,-1,0", "t.ies");
    const auto side = one_luminaire(tilt, "L,t.ies,0,3,0,1,0,0", "t.ies");
    CHECK(tilted.flux(tilted.luminaires[0]) == Approx(0.9 * level.flux(level.luminaires[0])));
    CHECK(side.flux(side.luminaires[0]) == Approx(0.8 * level.flux(level.luminaires[0])));
}

TEST_CASE("bad layouts are refused with LAYOUT:LINE") {
    const auto refused = [](const std::string& rows) {
        try {
            rad::build_luminaires({"lay.csv", rows, {{"lamp.ies", kIsotropic}}}, 1);
        } catch (const rad::InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refused("name,photometry,x,y\nL,lamp.ies,0,1\n")
              .rfind("lay.csv:1: the header line has no column 'z'", 0) == 0);
    CHECK(refused("name,photometry,x,y,z\nL,lamp.ies,0,one,0\n")
              .rfind("lay.csv:2: y is 'one', not a number", 0) == 0);
    CHECK(refused("name,photometry,x,y,z\nL,lamp.ies,0,1,0\nL,lamp.ies,1,1,0\n")
              .rfind("lay.csv:3: the name 'L' is used on line 2", 0) == 0);
    CHECK(refused("name,photometry,x,y,z\nL,../lamp.ies,0,1,0\n")
              .rfind("lay.csv:2: '../lamp.ies' leads out of the layout's folder", 0) == 0);
    CHECK(refused("name,photometry,x,y,z\nL,/etc/lamp.ies,0,1,0\n")
              .rfind("lay.csv:2: '/etc/lamp.ies' is an absolute path", 0) == 0);
    CHECK(refused("name,photometry,x,y,z,maintenance\nL,lamp.ies,0,1,0,1.5\n")
              .rfind("lay.csv:2: maintenance must be in (0, 1]", 0) == 0);
    CHECK(refused("name,photometry,x,y,z,aim_x,aim_y,aim_z\nL,lamp.ies,0,1,0,0,0,0\n")
              .rfind("lay.csv:2: the aim is the zero vector", 0) == 0);
    CHECK(refused("name,photometry,x,y,z,colour\nL,lamp.ies,0,1,0,red\n")
              .rfind("lay.csv:1: unknown column 'colour'", 0) == 0);
    CHECK(refused("name,photometry,x,y,z\n").rfind("lay.csv: the layout places no luminaire", 0) ==
          0);
    // As spreadsheets write them (#70 item 11): "CSV UTF-8" starts with a byte-order mark (it
    // was "has no column 'name'"); UTF-16 is named as such.
    CHECK(refused("\xEF\xBB\xBFname,photometry,x,y,z\nL,lamp.ies,0,1,0\n").empty());
    CHECK(refused(std::string("\xFF\xFEn\0a\0m\0e\0", 10))
              .rfind("lay.csv:1: is UTF-16 or UTF-32 text", 0) == 0);
    CHECK(refusal("\xFF\xFEI\0E\0S\0", "wide.ies").rfind("wide.ies:1: is UTF-16", 0) == 0);
    CHECK(refusal("\xEF\xBB\xBF" + std::string(kIsotropic), "bom.ies").empty());
    // A quoted cell holding a line break is one row over two lines, refused for what is
    // wrong with it at its first line (it was two rows: "no file named"); a quote never
    // closed is said as such, at the line it opened on.
    CHECK(refused("name,photometry,x,y,z\n\"L\n1\",lamp.ies,0,1,0\n")
              .rfind("lay.csv:2: 'L?1' is a name holding a control character", 0) == 0);
    CHECK(refused("name,photometry,x,y,z\nL,lamp.ies,0,1,0\nM,\"lamp.ies,1,1,0\n")
              .rfind("lay.csv:3: a double quote opened on this line is never closed", 0) == 0);
    CHECK(refused("name,photometry,x,y,z,group\nL,lamp.ies,0,1,0,\"a, b\"\nM,lamp.ies,1,1,0,c\n")
              .empty());
}

#include "radiosity/luminaire_image.hpp"

TEST_CASE("a luminaire's opening is drawn at its luminance, in front of the ceiling it sits in") {
    // A 0.2 x 0.2 m opening, 1000 cd straight down, flush with a ceiling at y = 3 (a plane
    // facing down); the camera below looks straight up at it.
    const std::string ies =
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0.2 0.2 0\n1 1 0\n0 90\n0\n1000 1000\n";
    auto ceiling = floor_mesh(5);
    for (auto& v : ceiling.vertices) v[1] = 3;
    std::swap(ceiling.vertices[1], ceiling.vertices[3]); // wound to face down
    ceiling.patches[0].normal = {0, -1, 0};
    ceiling.patches[0].centroid = {0, 3, 0};
    const rad::RayScene scene(ceiling);
    const auto set = one_luminaire(ies, "L,lamp.ies,0,3,0");
    rad::Image image;
    image.width = image.height = 33;
    image.rgb.assign(33 * 33 * 3, 0.5f);
    rad::View view;
    view.position = {0, 0, 0};
    view.direction = {0, 1, 0};
    view.up = {0, 0, -1};
    view.horizontal_deg = view.vertical_deg = 20;
    const auto changed = rad::draw_luminaires(image, set, scene, view, 1);
    // pi L = pi I / A, as W/m^2 of white (179 lm/W).
    const double expect = std::numbers::pi * 1000 / 0.04 / 179;
    const std::size_t centre = (16 * 33 + 16) * 3;
    CHECK(image.rgb[centre] == Approx(expect).epsilon(1e-4));
    CHECK(image.rgb[0] == 0.5f); // the corner sees the ceiling
    // The opening covers 0.2 / (2 x 3 tan 10 deg) of the view across: about 6 of 33 pixels.
    const double across = 0.2 / (2 * 3 * std::tan(10 * std::numbers::pi / 180)) * 33;
    CHECK(double(changed) == Approx(across * across).epsilon(0.35));
    // Dimmed by its group's weight (--mix).
    rad::Image dim = image;
    dim.rgb.assign(33 * 33 * 3, 0.5f);
    rad::draw_luminaires(dim, set, scene, view, 1, {radfmt::Rgb{{0.5, 0.5, 0.5}}});
    CHECK(dim.rgb[centre] == Approx(expect / 2).epsilon(1e-4));
}

#include "radiosity/formfactor.hpp"

TEST_CASE("near a large opening its light is sampled over it, as the exact form factor says") {
    // A 1 x 1 m Lambertian opening (I = I0 cos(gamma), I0 = L A) 0.5 m over a point: the
    // irradiance is L pi F, F the point's exact form factor to the square (contour integral);
    // a point source would read I0 / h^2, 27% more.
    const auto set = one_luminaire(cosine_ies("1 1"), "L,lamp.ies,0,0.5,0");
    const double luminance = 1000 / 1.0; // I0 / A
    const std::vector<rad::Vec3> square{
        {-0.5, 0.5, -0.5}, {0.5, 0.5, -0.5}, {0.5, 0.5, 0.5}, {-0.5, 0.5, 0.5}};
    for (const rad::Vec3 p : {rad::Vec3{0, 0, 0}, rad::Vec3{0.3, 0, 0.1}}) {
        const double f = rad::point_to_polygon_form_factor(p, {0, 1, 0}, square);
        const double exact = luminance * std::numbers::pi * f;
        const double near =
            rad::luminaire_illuminance(set, set.luminaires[0], p, {0, 1, 0}, nullptr);
        CHECK(near == Approx(exact).epsilon(0.01));
    }
    // Far away (over five openings) it is a point source: I0 cos^3 / h^2 exactly.
    const double far =
        rad::luminaire_illuminance(set, set.luminaires[0], {0, -5.5, 0}, {0, 1, 0}, nullptr);
    CHECK(far == Approx(1000 / 36.0).epsilon(1e-6));
}

TEST_CASE("EULUMDAT's lamp colour temperature tints the light, keeping its lumens") {
    // The floor uplight's lamp set says "nw/4200".
    const auto p = read("eulumdat-rs_floor_uplight_Isym0.ldt");
    CHECK(p.cct == 4200);
}

TEST_CASE("a luminous opening over 1 km is refused at its line, in IES and EULUMDAT (#70 item 7)") {
    const std::string ies =
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 1e300 0 0\n1 1 0\n0 180\n0\n1000 1000\n";
    CHECK_THAT(refusal(ies), Catch::Matchers::Contains("bad.ies:3:") &&
                                 Catch::Matchers::Contains("width is over 1000 m"));
    // A foot-based file: 3300 ft is over 1 km, 3000 ft is not.
    auto feet = [](const char* width) {
        return "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 1 " + std::string(width) +
               " 0 0\n1 1 0\n0 180\n0\n1000 1000\n";
    };
    CHECK_THAT(refusal(feet("3300")), Catch::Matchers::Contains("over 1000 m"));
    CHECK(refusal(feet("3000")).empty());
    // EULUMDAT's line 16 (length or diameter, mm) at 1e300.
    auto lines = slurp(kData / "eulumdat-ugr_sample_01_Isym4.ldt");
    std::size_t at = 0;
    for (int k = 1; k < 16; ++k) at = lines.find('\n', at) + 1;
    lines.replace(at, lines.find('\n', at) - at, "1e300");
    CHECK_THAT(refusal(lines, "big.ldt"), Catch::Matchers::Contains("big.ldt:16:") &&
                                              Catch::Matchers::Contains("over 1000 m"));
}

TEST_CASE("a .lum whose groups or count its layout does not make is refused (#70 item 8)") {
    const auto set = one_luminaire(kIsotropic, "L,lamp.ies,0,2,0,,,,,,downlights");
    REQUIRE(set.groups == std::vector<std::string>{"downlights"});
    CHECK_NOTHROW(rad::check_luminaires_file(set, {"downlights"}, 1, "a.lum"));
    CHECK_NOTHROW(rad::check_luminaires_file(set, {"downlights"}, -1, "a.lum"));
    CHECK_THROWS_WITH(rad::check_luminaires_file(set, {"downlights", "extra"}, 1, "a.lum"),
                      Catch::Matchers::Contains("a.lum: its light groups (downlights, extra) are "
                                                "not those its layout makes (downlights)"));
    CHECK_THROWS_WITH(rad::check_luminaires_file(set, {"downlights"}, 7, "a.lum"),
                      Catch::Matchers::Contains("records 7 luminaires, its layout places 1"));
}

// Melanopic light (CIE S 026:2018, #69 item 4): the standard's own constants and published
// ratios, a monochromatic line worked out by hand from the tabulated functions, and the bands
// adding up to the whole.
namespace {
fs::path spectrum_file(const std::string& name, const std::string& text) {
    const auto path = fs::temp_directory_path() / ("radiosity-test-" + name);
    std::ofstream(path) << text;
    return path;
}
} // namespace

TEST_CASE("melanopic efficacy of D65 and illuminant A is CIE S 026's", "[melanopic]") {
    // K_mel,v^D65 = 1.3262 mW/lm defines the D65 equivalent (from 1 nm tables; the 5 nm
    // ones give 1.32635); D65's mel-DER is 1.
    CHECK(rad::melanopic_elr(rad::cie_d65()) == Approx(1.3262).epsilon(2e-4));
    CHECK(rad::melanopic_der(rad::cie_d65()) == Approx(1).epsilon(1e-12));
    // Illuminant A: mel-DER 0.4958 (CIE S 026 Table 2; 100 lx of A is 49.58 lx melanopic EDI).
    CHECK(rad::melanopic_der(rad::cie_illuminant_a()) == Approx(0.4958).epsilon(0.005));
    // A blackbody at A's temperature (the other c2) is A within a hair.
    CHECK(rad::melanopic_der(rad::blackbody(2856)) ==
          Approx(rad::melanopic_der(rad::cie_illuminant_a())).epsilon(1e-3));
    // Warmer is less melanopic, and the order holds across lamps.
    CHECK(rad::melanopic_der(rad::blackbody(2700)) < rad::melanopic_der(rad::blackbody(4000)));
    CHECK(rad::melanopic_der(rad::blackbody(4000)) < rad::melanopic_der(rad::blackbody(6500)));
}

TEST_CASE("a spectrum CSV: a line at 490 nm weighed by hand", "[melanopic]") {
    // Only 490 nm: mel-DER = (s_mel(490) / V(490)) / (K_m x K_mel,v^D65) with s_mel(490) = 1
    // and V(490) = 0.20802 (CIE tables): 1 / 0.20802 / (683.002 x 1.3262e-3) = 5.307.
    const auto path = spectrum_file("line.csv", "wavelength_nm,power\n485,0\n490,1\n495,0\n");
    const auto line = rad::read_spectrum_csv(path.string());
    CHECK(rad::melanopic_der(line) == Approx(1 / 0.20802 / (683.002 * 1.3262e-3)).epsilon(2e-4));
    // The bands add up to the whole, and a sample on a band's edge counts half to each side.
    const auto bands = rad::melanopic_der_bands(line);
    CHECK(bands[0] == 0);
    CHECK(bands[1] == Approx(bands[2]));
    CHECK(bands[0] + bands[1] + bands[2] == Approx(rad::melanopic_der(line)));
    const auto d65 = rad::melanopic_der_bands(rad::cie_d65());
    CHECK(d65[0] + d65[1] + d65[2] == Approx(1).epsilon(1e-12));
    CHECK(d65[2] > d65[0]); // the melanopic stimulus is blue and green, hardly red
    fs::remove(path);
}

TEST_CASE("melanopic EDI from the chain's RGB: grey rooms give E x mel-DER", "[melanopic]") {
    const rad::Rgb grey{2, 2, 2}; // W/m^2 per channel: 358 lx
    for (const auto& s : {rad::cie_d65(), rad::cie_illuminant_a(), rad::blackbody(4000)}) {
        const auto w = rad::melanopic_weights(s, {1, 1, 1});
        CHECK(rad::melanopic_edi(grey, w) == Approx(rad::lux(grey) * rad::melanopic_der(s)));
    }
    // A tinted lamp's own colour is divided out: its light on grey walls is still E x DER.
    const rad::Rgb tint{1.4, 0.95, 0.6};
    const auto a = rad::cie_illuminant_a();
    const auto w = rad::melanopic_weights(a, tint);
    const rad::Rgb lit{3 * tint[0], 3 * tint[1], 3 * tint[2]};
    CHECK(rad::melanopic_edi(lit, w) == Approx(rad::lux(lit) * rad::melanopic_der(a)));
    // A blue wall passes the blue band: more melanopic light per lux than the lamp itself.
    const rad::Rgb blue{0.1 * tint[0], 0.3 * tint[1], 0.9 * tint[2]};
    CHECK(rad::melanopic_edi(blue, w) / rad::lux(blue) > rad::melanopic_der(a));
}

TEST_CASE("spectra that cannot be read are refused at FILE:LINE", "[melanopic]") {
    const auto down = spectrum_file("down.csv", "400,1\n500,1\n450,1\n");
    CHECK_THROWS_WITH(rad::read_spectrum_csv(down.string()),
                      Catch::Matchers::Contains("down.csv:3: wavelength 450 nm does not increase"));
    const auto negative = spectrum_file("negative.csv", "400,1\n500,-1\n");
    CHECK_THROWS_WITH(rad::read_spectrum_csv(negative.string()),
                      Catch::Matchers::Contains("negative.csv:2: spectral power -1"));
    const auto junk = spectrum_file("junk.csv", "nm,power\n400,1\nhello\n");
    CHECK_THROWS_WITH(rad::read_spectrum_csv(junk.string()),
                      Catch::Matchers::Contains("junk.csv:3: expected 'wavelength_nm,value'"));
    const auto infrared = spectrum_file("ir.csv", "800,1\n900,1\n");
    CHECK_THROWS_WITH(rad::read_spectrum_csv(infrared.string()),
                      Catch::Matchers::Contains("no visible light"));
    CHECK_THROWS_WITH(rad::parse_spectrum("cct:100"),
                      Catch::Matchers::Contains("within 1000 to 25000 K"));
    CHECK_THROWS_WITH(rad::parse_spectrum("cct:warm"), Catch::Matchers::Contains("cct:K takes"));
    for (const auto& p : {down, negative, junk, infrared}) fs::remove(p);
}
