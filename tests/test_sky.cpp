// The sky and the sun against published and closed-form values: SPA's own example, the
// uniform and CIE overcast skies' horizontal illuminance, the sky patches' coverage and their
// mean luminances integrating to the sky's illuminance, and the EPW reader.
#include "helpers.hpp"
#include "radiosity/build_mesh.hpp"
#include "radiosity/daylight.hpp"
#include "radiosity/daylight_glare.hpp"
#include "radiosity/en17037.hpp"
#include "radiosity/error.hpp"
#include "radiosity/shading.hpp"
#include "radiosity/sky.hpp"
#include "radiosity/sky_patches.hpp"
#include "radiosity/sunlight_exposure.hpp"
#include "radiosity/weather.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

using namespace testing_helpers;

namespace {
constexpr double kPi = std::numbers::pi;

// Sum of a patch value x its cosine-weighted solid angle, integrated on a fine grid.
double horizontal_of(const rad::SkyPatches& patches, const std::vector<double>& luminance) {
    double total = 0;
    for (std::size_t p = 1; p < patches.count(); ++p) {
        const auto b = patches.bounds(p);
        const double s0 = std::sin(b.altitude0 * kPi / 180), s1 = std::sin(b.altitude1 * kPi / 180);
        total += luminance[p] * 0.5 * (s1 * s1 - s0 * s0) * (b.azimuth1 - b.azimuth0) * kPi / 180;
    }
    return total;
}
} // namespace

TEST_CASE("solar position matches SPA's published example", "[sky]") {
    // Reda and Andreas (2008), the example of section A5: 17 October 2003, 12:30:30 at
    // UTC-7, 39.742476 N, 105.1786 W, 1830.14 m, 820 mbar, 11 C, delta T 67 s.
    rad::Location at;
    at.latitude = 39.742476;
    at.longitude = -105.1786;
    at.time_zone = -7;
    at.elevation = 1830.14;
    at.pressure = 820;
    at.temperature = 11;
    const auto sun = rad::solar_position(at, {2003, 10, 17, 12 + 30 / 60.0 + 30 / 3600.0}, 67);
    CHECK(sun.zenith == Approx(50.11162).margin(0.01));
    CHECK(sun.azimuth == Approx(194.34024).margin(0.01));
    // Far tighter than asked: the algorithm is the report's.
    CHECK(sun.zenith == Approx(50.11162).margin(2e-5));
    CHECK(sun.azimuth == Approx(194.34024).margin(2e-5));
}

TEST_CASE("the compass: north, east and back", "[sky]") {
    const rad::SkyFrame frame{30};
    double alt = 0, az = 0;
    const auto d = frame.direction(40, 200);
    frame.angles(d, alt, az);
    CHECK(alt == Approx(40));
    CHECK(az == Approx(200));
    const rad::SkyFrame plain;
    CHECK(plain.direction(0, 0)[2] == Approx(-1)); // north is -Z
    CHECK(plain.direction(0, 90)[0] == Approx(1)); // east is +X
}

TEST_CASE("skies integrate to their horizontal illuminance", "[sky]") {
    const rad::SkyFrame frame;
    SECTION("uniform: pi L") {
        const auto sky = rad::Sky::uniform(1000, frame, 0.2);
        CHECK(sky.horizontal_illuminance() == Approx(kPi * 1000));
        CHECK(sky.ground_luminance() == Approx(0.2 * kPi * 1000 / kPi));
    }
    SECTION("CIE overcast: 7 pi Lz / 9, and (1 + 2 sin a) / 3 of Lz") {
        const auto sky = rad::Sky::cie_overcast(10000, frame, 0.2);
        const double lz = sky.zenith_luminance();
        CHECK(7 * kPi * lz / 9 == Approx(10000));
        CHECK(sky.luminance_at(30, 77) == Approx(lz * (1 + 2 * 0.5) / 3));
        CHECK(sky.luminance_at(0.001, 0) == Approx(lz / 3).epsilon(1e-4));
    }
    SECTION("a CIE standard sky's zenith and its scale") {
        rad::SunPosition sun;
        sun.zenith = 40;
        sun.azimuth = 180;
        for (int type = 1; type <= 15; ++type) {
            const auto sky = rad::Sky::cie_standard(type, sun, 20000, frame, 0.2);
            // The luminance at the zenith relative to itself is 1 by the definition.
            CHECK(sky.relative(0, 40 * kPi / 180) == Approx(1));
            CHECK(sky.horizontal_illuminance() == Approx(20000));
        }
        CHECK_THROWS_AS(rad::Sky::cie_standard(16, sun, 1, frame, 0.2), rad::InputError);
    }
}

TEST_CASE("Reinhart patches: counts, coverage, solid angles", "[sky]") {
    for (int m : {1, 2, 4}) {
        const rad::SkyPatches patches(m);
        CHECK(patches.count() == 144 * std::size_t(m * m) + 2);
        double total = 0;
        for (std::size_t p = 1; p < patches.count(); ++p) total += patches.solid_angle(p);
        CHECK(total == Approx(2 * kPi));
        // Every patch's own cells fall in it.
        const rad::SkyFrame frame{17};
        for (std::size_t p = 0; p < patches.count(); p += 7)
            for (const auto& d : patches.cell_directions(frame, p, 3))
                CHECK(patches.patch_of(frame, d) == p);
    }
    CHECK(rad::SkyPatches::parse("tregenza").count() == 146);
    CHECK(rad::SkyPatches::parse("reinhart:2").count() == 578);
    CHECK_THROWS_AS(rad::SkyPatches::parse("reinhart:0"), rad::InputError);
    CHECK_THROWS_AS(rad::SkyPatches::parse("klems"), rad::InputError);
}

TEST_CASE("a sky's patch luminances integrate to its horizontal illuminance", "[sky]") {
    const rad::SkyFrame frame{10};
    rad::SunPosition sun;
    sun.zenith = 35;
    sun.azimuth = 150;
    std::vector<rad::Sky> skies{rad::Sky::cie_overcast(10000, frame, 0.2),
                                rad::Sky::uniform(3000, frame, 0.2)};
    for (int type : {1, 5, 12, 15})
        skies.push_back(rad::Sky::cie_standard(type, sun, 15000, frame, 0.2));
    skies.push_back(rad::Sky::perez(700, 120, sun, 180, 8, frame, 0.2)); // clear
    skies.push_back(rad::Sky::perez(50, 300, sun, 180, 8, frame, 0.2));  // overcast
    for (int m : {1, 2}) {
        const rad::SkyPatches patches(m);
        for (const auto& sky : skies) {
            INFO(sky.describe() << " at reinhart:" << m);
            CHECK(horizontal_of(patches, patches.mean_luminance(sky)) ==
                  Approx(sky.horizontal_illuminance()).epsilon(0.005));
        }
    }
}

TEST_CASE("Perez sky: efficacies in the published range, the sun's beam", "[sky]") {
    const rad::SkyFrame frame;
    rad::SunPosition sun;
    sun.zenith = 30;
    sun.azimuth = 180;
    const auto clear = rad::Sky::perez(800, 100, sun, 172, 10, frame, 0.2);
    // Luminous efficacy of diffuse light 100-150 lm/W, of the beam 80-110 lm/W.
    CHECK(clear.horizontal_illuminance() / 100 > 100);
    CHECK(clear.horizontal_illuminance() / 100 < 150);
    CHECK(clear.sun_normal_illuminance() / 800 > 80);
    CHECK(clear.sun_normal_illuminance() / 800 < 110);
    // The circumsolar sky is brighter than the sky opposite the sun.
    CHECK(clear.luminance_at(55, 180) > 3 * clear.luminance_at(55, 0));
    sun.zenith = 95;
    const auto night = rad::Sky::perez(0, 0, sun, 172, 10, frame, 0.2);
    CHECK(night.horizontal_illuminance() == 0);
    CHECK(night.sun_normal_illuminance() == 0);
}

TEST_CASE("EPW: the fixture's location and a year of hours; malformed files named", "[sky]") {
    const std::string fixture = std::string(RADIOSITY_SOURCE_DIR) + "/tests/data/denver-tmy3.epw";
    const auto w = rad::read_epw(fixture);
    CHECK(w.location.latitude == Approx(39.83));
    CHECK(w.location.longitude == Approx(-104.65));
    CHECK(w.location.time_zone == Approx(-7));
    REQUIRE(w.hours.size() == 8760);
    CHECK(w.hours[12].month == 1);
    CHECK(w.hours[12].hour == 13);
    const auto noon = rad::sun_of_hour(w, w.hours[4380]); // 1 July, 12:00-13:00
    CHECK(noon.zenith < 30);
    const auto dir = std::filesystem::temp_directory_path() / "radiosity_test_sky";
    std::filesystem::create_directories(dir);
    const auto bad = (dir / "bad.epw").string();
    {
        std::ifstream in(fixture);
        std::ofstream out(bad);
        std::string line;
        for (int k = 0; std::getline(in, line); ++k)
            out << (k == 20 ? line.substr(0, 40) : line) << '\n';
    }
    try {
        rad::read_epw(bad);
        FAIL("a truncated record was read");
    } catch (const rad::InputError& e) {
        CHECK(std::string(e.what()).find(bad + ":21:") == 0);
    }
}

namespace {
const char* kBlackMtl = "newmtl black\nKd 0 0 0\n";

std::string quad_obj(std::string& obj, int& count, const std::vector<rad::Vec3>& corners) {
    for (const auto& c : corners)
        obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
               std::to_string(c[2]) + "\n";
    obj += "f " + std::to_string(count + 1) + " " + std::to_string(count + 2) + " " +
           std::to_string(count + 3) + " " + std::to_string(count + 4) + "\n";
    count += 4;
    return obj;
}

radfmt::MeshData black_mesh(const std::string& obj, double max_edge = 0) {
    rad::SubdivisionOptions options;
    options.max_edge = max_edge;
    return rad::subdivide(scene_from_obj("usemtl black\n" + obj, kBlackMtl, "sky_mesh"), options);
}

// A black room 4 x 4 x 1 (y up) whose ceiling has a 1 m x 1 m opening over the floor's centre.
radfmt::MeshData roof_opening_room(double max_edge = 0) {
    std::string obj;
    int n = 0;
    const double a = 2, h = 1, o = 0.5;
    quad_obj(obj, n, {{-a, 0, -a}, {-a, 0, a}, {a, 0, a}, {a, 0, -a}}); // floor, up
    // The ceiling around the opening, facing down: four rectangles.
    quad_obj(obj, n, {{-a, h, -a}, {a, h, -a}, {a, h, -o}, {-a, h, -o}});
    quad_obj(obj, n, {{-a, h, o}, {a, h, o}, {a, h, a}, {-a, h, a}});
    quad_obj(obj, n, {{-a, h, -o}, {-o, h, -o}, {-o, h, o}, {-a, h, o}});
    quad_obj(obj, n, {{o, h, -o}, {a, h, -o}, {a, h, o}, {o, h, o}});
    quad_obj(obj, n, {{-a, 0, -a}, {a, 0, -a}, {a, h, -a}, {-a, h, -a}}); // walls, inward
    quad_obj(obj, n, {{-a, 0, a}, {-a, h, a}, {a, h, a}, {a, 0, a}});
    quad_obj(obj, n, {{-a, 0, -a}, {-a, h, -a}, {-a, h, a}, {-a, 0, a}});
    quad_obj(obj, n, {{a, 0, -a}, {a, 0, a}, {a, h, a}, {a, h, -a}});
    return black_mesh(obj, max_edge);
}

rad::DaylightSolution dark_solution(const radfmt::MeshData& mesh) {
    rad::DaylightSolution s{rad::SkyPatches(1), rad::SkyFrame{}, {}};
    s.radiosity.assign(mesh.patches.size() * s.patches.count() * 3, 0.0f);
    return s;
}
} // namespace

TEST_CASE("an unobstructed sensor reads pi L under a uniform sky, 7 pi Lz / 9 under the CIE "
          "overcast sky",
          "[sky]") {
    std::string obj;
    int n = 0;
    quad_obj(obj, n, {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}});
    const auto mesh = black_mesh(obj);
    const rad::DaylightSensors sensors(mesh, dark_solution(mesh), {});
    const rad::Vec3 at{0, 0.01, 0}, up{0, 1, 0};
    const auto uniform = rad::Sky::uniform(2000, rad::SkyFrame{}, 0.2);
    CHECK(sensors.illuminance(uniform, at, up, 0).total() == Approx(kPi * 2000).epsilon(0.005));
    const auto overcast = rad::Sky::cie_overcast(12000, rad::SkyFrame{}, 0.2);
    const double lz = overcast.zenith_luminance();
    CHECK(sensors.illuminance(overcast, at, up, 0).total() ==
          Approx(7 * kPi * lz / 9).epsilon(0.005));
    // The daylight coefficients give the same through the patches' mean luminances.
    const auto c = sensors.coefficients(at, up, 0);
    const auto mean = sensors.patches().mean_luminance(overcast);
    double through = 0;
    for (std::size_t s = 0; s < mean.size(); ++s) through += c.direct[s] * mean[s];
    CHECK(through == Approx(7 * kPi * lz / 9).epsilon(0.005));
}

TEST_CASE("a sensor under a 1 m x 1 m roof opening reads the sky integrated over the opening "
          "(CIE 171:2006's sky component case)",
          "[sky]") {
    const auto mesh = roof_opening_room();
    rad::SunPosition sun;
    sun.zenith = 20; // the sun's corona seen through the opening, the hard case
    sun.azimuth = 180;
    for (int type : {1, 5, 12}) {
        const auto sky = rad::Sky::cie_standard(type, sun, 20000, rad::SkyFrame{}, 0.2);
        // Independent: E = integral over the opening of L(d) h^2 / r^4 (the sensor h = 0.99 m
        // below its centre), by the midpoint rule on 400 x 400 cells.
        constexpr int kCells = 400;
        constexpr double h = 0.99;
        double expected = 0;
        for (int i = 0; i < kCells; ++i)
            for (int k = 0; k < kCells; ++k) {
                const double x = -0.5 + (i + 0.5) / kCells, z = -0.5 + (k + 0.5) / kCells;
                const double r2 = x * x + h * h + z * z, r = std::sqrt(r2);
                expected +=
                    sky.luminance({x / r, h / r, z / r}) * h * h / (r2 * r2) / (kCells * kCells);
            }
        for (int samples : {64, 256}) {
            rad::DaylightOptions options;
            options.sky_side = int(std::sqrt(samples));
            const rad::DaylightSensors sensors(mesh, dark_solution(mesh), options);
            const auto got = sensors.illuminance(sky, {0, 0.01, 0}, {0, 1, 0}, 0).total();
            INFO("CIE type " << type << ", " << samples << " directions per sky patch: " << got
                             << " lux, expected " << expected);
            CHECK(got == Approx(expected).epsilon(0.01));
        }
    }
}

TEST_CASE("patches' sky view conserves the flux through an opening, deterministically", "[sky]") {
    // The uniform sky of unit radiance sends pi x 1 m^2 through the 1 m x 1 m roof opening,
    // all of it onto the black room's patches: sum over patches and sky patches of D A = pi.
    const auto mesh = roof_opening_room(0.25);
    const rad::RayScene scene(mesh);
    const rad::SpecularSurfaces specular(mesh);
    rad::SkyViewOptions options{rad::SkyPatches(1), rad::SkyFrame{}, 4096, 1, 12};
    const auto view = rad::patch_sky_view(mesh, scene, specular, options, 0, mesh.patches.size());
    const std::size_t count = options.patches.count();
    double flux = 0, ground = 0;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        for (std::size_t s = 0; s < count; ++s) {
            flux += rad::luminous(view[i * count + s]) * mesh.patches[i].area;
            if (s == 0) ground += rad::luminous(view[i * count]) * mesh.patches[i].area;
        }
    CHECK(flux == Approx(kPi).epsilon(0.01));
    // Nothing inside sees below the horizon through a roof, but for rays from a wall's very
    // edge that start past the floor it meets (the hemisphere method's own leak at contacts).
    CHECK(ground < 0.002 * kPi);
    // The same bytes for a part of the rows.
    const auto part = rad::patch_sky_view(mesh, scene, specular, options, 3, 5);
    for (std::size_t k = 0; k < part.size(); ++k) CHECK(part[k] == view[3 * count + k]);
}

TEST_CASE("the daylight basis reproduces the skies it was made for, better with more components",
          "[sky]") {
    // A made-up solution: 40 patches, Tregenza's 146 groups, values from a fixed sequence.
    rad::DaylightSolution solution{rad::SkyPatches(1), rad::SkyFrame{}, {}};
    const std::size_t count = solution.patches.count(), n = 40;
    std::uint64_t state = 12345;
    const auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53;
    };
    for (std::size_t k = 0; k < n * count * 3; ++k) solution.radiosity.push_back(float(next()));
    std::vector<double> areas(n);
    for (auto& a : areas) a = 0.5 + next();
    std::vector<std::vector<double>> skies(12, std::vector<double>(count));
    for (auto& sky : skies)
        for (auto& l : sky) l = 1000 * next();
    // As many components as skies: exact (to the square root of rounding: the error is
    // sqrt(|y|^2 - sum of c^2)); fewer: an error that never grows with more.
    const auto full = rad::daylight_basis(solution, areas, skies, 64, 0);
    CHECK(full.values.size() == skies.size());
    CHECK(full.worst_error < 1e-4);
    double previous = 2;
    for (int k = 1; k <= 12; k += 3) {
        const auto basis = rad::daylight_basis(solution, areas, skies, k, 0);
        CHECK(basis.values.size() == std::size_t(k));
        CHECK(basis.mean_error <= previous + 1e-12);
        previous = basis.mean_error;
    }
    // The error it reports is the one its radiosity has: sky 3 through 4 components.
    const auto four = rad::daylight_basis(solution, areas, skies, 4, 0);
    const auto& sky = skies[3];
    double diff = 0, norm = 0;
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t c = 0; c < 3; ++c) {
            double exact = 0, approx = 0;
            for (std::size_t s = 0; s < count; ++s)
                exact += sky[s] / 179 * solution.radiosity[(j * count + s) * 3 + c];
            for (std::size_t k = 0; k < four.values.size(); ++k) {
                double w = 0;
                for (std::size_t s = 0; s < count; ++s) w += four.weights[k][s] * sky[s];
                approx += w * four.values[k][j][c];
            }
            diff += areas[j] * (exact - approx) * (exact - approx);
            norm += areas[j] * exact * exact;
        }
    const double error = std::sqrt(diff / norm);
    CHECK(error <= four.worst_error + 1e-9);
    CHECK(error > 0.01); // four components of twelve random skies cannot be exact
}

TEST_CASE("skies, places and times out of range are refused, not taken as light (#70 items 5, 6)",
          "[sky]") {
    const rad::SkyFrame frame;
    rad::SunPosition sun;
    sun.zenith = 40;
    sun.azimuth = 180;
    const auto refusal = [&](const std::string& spec) {
        try {
            rad::parse_sky(spec, &sun, 172, frame, 0.2);
        } catch (const rad::InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // 1e308 made NaN lux; now each names its option and range.
    CHECK_THAT(refusal("uniform:1e308"),
               Catch::Contains("--sky uniform:L (cd/m^2): 1e+308 is outside"));
    CHECK_THAT(refusal("cie-overcast:1e308"), Catch::Contains("--sky cie-overcast:LUX"));
    CHECK_THAT(refusal("cie:12:1e308"), Catch::Contains("--sky cie:TYPE:LUX"));
    CHECK_THAT(refusal("cie-overcast:-5"), Catch::Contains("outside 0"));
    CHECK_THAT(refusal("perez:1e300,20"), Catch::Contains("DNI"));
    CHECK(refusal("cie-overcast:20000").empty());
    CHECK(refusal("perez:800,100").empty());
    // Calendar days and clock times only.
    CHECK_THROWS_AS(rad::parse_local_time("2023-02-31", "12:00"), rad::InputError);
    CHECK_THROWS_AS(rad::parse_local_time("2023-02-29", "12:00"), rad::InputError);
    CHECK_NOTHROW(rad::parse_local_time("2024-02-29", "12:00"));
    CHECK_THROWS_AS(rad::parse_local_time("2023-06-21", "24:59"), rad::InputError);
    CHECK_NOTHROW(rad::parse_local_time("2023-06-21", "24:00"));
    CHECK_THROWS_AS(rad::parse_local_time("99999-06-21", "12:00"), rad::InputError);
    CHECK_THROWS_WITH(rad::parse_location("40,-105,-7,1e308"),
                      Catch::Contains("an elevation of 1e+308 m is outside"));
    CHECK(rad::parse_location("40,-105,-7,1600").elevation == 1600);
}

TEST_CASE("Perez's sky holds over every hour a weather file can hold (#70 item 6)", "[sky]") {
    const rad::SkyFrame frame;
    rad::SunPosition sun;
    sun.azimuth = 180;
    // 11 Jul 12:00 of a real EPW: DNI 120, DHI 46 W/m^2, the sun at 72 degrees. Its Perez
    // distribution is negative over the whole sky at the hour's brightness: the year stopped.
    sun.zenith = 18;
    const auto hour = rad::Sky::perez(120, 46, sun, 192, 10, frame, 0.2);
    CHECK(hour.horizontal_illuminance() > 0);
    CHECK_THAT(hour.adjusted(), Catch::Contains("taken at"));
    // Every combination over the sun's zenith, DNI and DHI gives a sky.
    int refused = 0;
    for (double z = 0; z < 90; z += 6)
        for (double dni = 0; dni <= 1000; dni += 50)
            for (double dhi = 1; dhi <= 500; dhi += 15) {
                sun.zenith = z;
                try {
                    const auto sky = rad::Sky::perez(dni, dhi, sun, 192, 10, frame, 0.2);
                    CHECK(std::isfinite(sky.horizontal_illuminance()));
                } catch (const rad::InputError&) {
                    ++refused;
                }
            }
    CHECK(refused == 0);
    // No diffuse light with the sun up: the beam is kept (it gave 0 lx).
    sun.zenith = 30;
    const auto beam_only = rad::Sky::perez(800, 0, sun, 172, 10, frame, 0.2);
    CHECK(beam_only.sun_normal_illuminance() > 800 * 80);
    CHECK(beam_only.horizontal_illuminance() == 0);
    // An ordinary hour is not adjusted.
    CHECK(rad::Sky::perez(700, 120, sun, 172, 10, frame, 0.2).adjusted().empty());
}

TEST_CASE("EN 17037's daylight factor method: the levels' daylight factors and shares") {
    // E_v,d,med 15000 lx: minimum 2% over half, 0.667% over 95%; medium 3.33% / 2%; high 5% /
    // 3.33%. 100 points: 60 at 4%, 38 at 2.5%, 2 at 0.5%.
    std::vector<double> df(60, 4.0);
    df.insert(df.end(), 38, 2.5);
    df.insert(df.end(), 2, 0.5);
    df.push_back(std::nan("")); // a point inside furniture: in no share
    const auto p = rad::en17037_daylight_provision(df, 15000);
    CHECK(p.levels[0].target_df == Approx(2));
    CHECK(p.levels[0].minimum_df == Approx(100.0 * 100 / 15000));
    CHECK(p.levels[0].target_share == Approx(0.98));
    CHECK(p.levels[0].minimum_share == Approx(0.98));
    CHECK(p.levels[0].met);
    CHECK(p.levels[1].target_share == Approx(0.60));  // 4% >= 3.33%
    CHECK(p.levels[1].minimum_share == Approx(0.98)); // 2.5% >= 2%
    CHECK(p.levels[1].met);
    CHECK(p.levels[2].target_share == Approx(0.0)); // none at 5%
    CHECK_FALSE(p.levels[2].met);
    CHECK(p.achieved() == "medium");
    CHECK_THROWS_AS(rad::en17037_daylight_provision(df, 0), rad::InputError);
}

TEST_CASE("EN 17037's median external diffuse illuminance: the median of the brightest half") {
    rad::Weather w;
    w.path = "fake.epw";
    for (int k = 0; k < 8760; ++k) {
        rad::WeatherHour h;
        h.diffuse_illuminance = double(k % 100) * 100; // 0..9900 lx
        w.hours.push_back(h);
    }
    // The 4380 brightest of 8760; their median lies between the 2190th and 2191st brightest.
    const auto m = rad::median_external_diffuse_illuminance(w);
    CHECK(m.source == "the weather file's diffuse horizontal illuminance");
    std::vector<double> all;
    for (const auto& h : w.hours) all.push_back(h.diffuse_illuminance);
    std::sort(all.begin(), all.end(), std::greater<>());
    CHECK(m.lux == Approx(0.5 * (all[2189] + all[2190])));
    // One hour without it: the file's radiation by Perez's efficacy instead (all dark here).
    w.hours[5].diffuse_illuminance = -1;
    CHECK(rad::median_external_diffuse_illuminance(w).source.find("Perez") != std::string::npos);
}

TEST_CASE("LM-83's blinds, replayed by hand on a small year: down when more than 2% of the "
          "sensors get 1000 lx or more of direct sun (#69 item 1)",
          "[sky]") {
    // 50 sensors, 7 hours; sensor 49 is inside an object (not judged), so one sunlit sensor
    // of the 49 judged is 2.04%: more than 2%.
    const std::size_t n = 50, hours = 7;
    radfmt::AnnualData open;
    open.positions.assign(n, radfmt::Vec3{0, 0, 0});
    open.normals.assign(n, radfmt::Vec3{0, 1, 0});
    for (std::uint32_t t = 0; t < hours; ++t) open.hours.push_back(10100 + t);
    open.occupied.assign(hours, 1);
    open.lux.assign(hours * n, 500.0f);
    open.sun_lux.assign(hours * n, 0.0f);
    const auto sun = [&](std::size_t t, std::size_t k, float lux) {
        open.sun_lux[t * n + k] = lux;
        open.lux[t * n + k] = 500 + lux;
    };
    // hour 0: no sun. hour 1: one sensor of 49 sunlit (2.04%: more than 2%). hour 2: one
    // sensor at 999.9 lx. hour 3: the only sunlit sensor is the one not judged. hour 4: three
    // sensors at exactly 1000 lx. hour 5: a sensor at 800 lx and one not judged at 9000 lx.
    // hour 6: every judged sensor at 20000 lx.
    sun(1, 3, 5000);
    sun(2, 7, 999.9f);
    sun(3, 49, 8000);
    for (std::size_t k : {10, 11, 12}) sun(4, k, 1000);
    sun(5, 20, 800);
    sun(5, 49, 9000);
    for (std::size_t k = 0; k < 49; ++k) sun(6, k, 20000);
    std::vector<std::uint8_t> judged(n, 1);
    judged[49] = 0;
    const auto rule = rad::parse_shading_rule("lm83", hours);
    const auto down = rad::shaded_hours(rule, open, judged);
    CHECK(down == std::vector<std::uint8_t>{0, 1, 0, 0, 1, 0, 1});
    // With all 50 judged, hour 1's one sensor is exactly 2%: not more, so the blinds stay up;
    // hour 3's sensor now counts (2%: up as well).
    const auto all = rad::shaded_hours(rule, open, std::vector<std::uint8_t>(n, 1));
    CHECK(all == std::vector<std::uint8_t>{0, 0, 0, 0, 1, 0, 1});
    // A rule of the user's: 900 lx on more than 1% (half a sensor): hour 5's 800 lx is not.
    const auto user = rad::shaded_hours(rad::parse_shading_rule("sun:900:1", hours), open, judged);
    CHECK(user == std::vector<std::uint8_t>{0, 1, 1, 0, 1, 0, 1});

    // The year as operated: the closed state's light in the hours down, the open state's sun.
    radfmt::AnnualData closed = open;
    for (auto& v : closed.lux) v = v / 20;
    for (auto& v : closed.sun_lux) v = v / 20;
    const auto year = rad::operated_year(open, closed, down);
    for (std::size_t t = 0; t < hours; ++t)
        for (std::size_t k = 0; k < n; ++k) {
            CHECK(year.lux[t * n + k] == (down[t] ? closed : open).lux[t * n + k]);
            CHECK(year.sun_lux[t * n + k] == open.sun_lux[t * n + k]);
        }
    // ASE is the open state's. Sensor 30's DA300 loses hours 1 and 4 (500 / 20 lx behind the
    // blinds), not hour 6 (its 20500 lx of sun and sky give 1025 lx through them).
    const auto m = rad::annual_metrics(year);
    const auto m_open = rad::annual_metrics(open);
    CHECK(m.sensors[0].sun_hours == m_open.sensors[0].sun_hours);
    CHECK(m.sensors[30].da300 == Approx(5.0 / 7));
    CHECK(m_open.sensors[30].da300 == 1.0);
}

TEST_CASE("shading rules that cannot be read are refused, naming the fix", "[sky]") {
    CHECK_THROWS_WITH(rad::parse_shading_rule("blinds", 24), Catch::Contains("give lm83"));
    CHECK_THROWS_WITH(rad::parse_shading_rule("sun:1000", 24), Catch::Contains("sun:LUX:PERCENT"));
    CHECK_THROWS_WITH(rad::parse_shading_rule("sun:x:2", 24), Catch::Contains("LUX 'x'"));
    CHECK_THROWS_WITH(rad::parse_shading_rule("sun:1000:100", 24), Catch::Contains("under 100"));
    CHECK_THROWS_WITH(rad::parse_shading_rule("sun:1000:-1", 24), Catch::Contains("PERCENT '-1'"));
    const auto path = std::filesystem::temp_directory_path() / "rad-test-shading-schedule.txt";
    std::ofstream(path) << "# down at noon\n0\n1\n2\n";
    CHECK_THROWS_WITH(rad::parse_shading_rule("schedule:" + path.string(), 3),
                      Catch::Contains(path.string() + ":4: a shading schedule line is 0 or 1"));
    std::ofstream(path) << "0\n1\n";
    CHECK_THROWS_WITH(rad::parse_shading_rule("schedule:" + path.string(), 3),
                      Catch::Contains("2 hours of shading schedule; the weather file has 3"));
    std::ofstream(path) << "0\n1\n1\n";
    CHECK(rad::parse_shading_rule("schedule:" + path.string(), 3).schedule ==
          std::vector<std::uint8_t>{0, 1, 1});
    std::filesystem::remove(path);
}

TEST_CASE("DGP: the formula with evalglare's constants, the low-light correction, the position "
          "index above (Guth) and below (Iwata) the line of sight (#69 item 2)",
          "[sky]") {
    rad::GlareSource source;
    source.luminance = 5000;
    source.solid_angle = 0.05;
    source.position_index = 1.5;
    // 0.159 + 5.87e-5 x 2000 + 0.092 log10(1 + 5000^2 x 0.05 / 1.5^2 / 2000^1.87), by hand.
    CHECK(rad::daylight_glare_probability(2000, {source}, true) == Approx(0.289068).epsilon(1e-5));
    CHECK(rad::daylight_glare_probability(2000, {}, true) == Approx(0.159 + 5.87e-5 * 2000));
    double factor = 0;
    rad::daylight_glare_probability(500, {source}, true, &factor);
    CHECK(factor == Approx(0.999665).epsilon(1e-5)); // exp(8) / (1 + exp(8))
    rad::daylight_glare_probability(100, {source}, true, &factor);
    CHECK(factor == Approx(0.167982).epsilon(1e-5));
    rad::daylight_glare_probability(100, {source}, false, &factor);
    CHECK(factor == 1);
    CHECK(rad::daylight_glare_probability(1e6, {source}, true) == 1); // capped
    const rad::Vec3 view{1, 0, 0}, up{0, 1, 0};
    const auto toward = [](double elevation_deg) {
        const double e = elevation_deg * kPi / 180;
        return rad::Vec3{std::cos(e), std::sin(e), 0};
    };
    CHECK(rad::dgp_position_index(view, up, view) == Approx(1));
    double sigma = 0, tau = 0;
    // 30 degrees straight above: Guth's exp((35.2 - 1.22) 1e-3 x 30 + 21e-5 x 30^2).
    CHECK(rad::dgp_position_index(view, up, toward(30), &sigma, &tau) ==
          Approx(3.348123).epsilon(1e-5));
    CHECK(sigma == Approx(30));
    CHECK(tau == Approx(0).margin(1e-6));
    // 30 degrees straight below: Iwata's, beta = atan(tan 30 sqrt(1 + 0.3225)) = 33.58 deg.
    CHECK(rad::dgp_position_index(view, up, toward(-30), &sigma, &tau) ==
          Approx(1.575828).epsilon(1e-5));
    CHECK(tau == Approx(180));
    // Far to the side and up: capped at 16.
    CHECK(rad::dgp_position_index(view, up, rad::normalized(rad::Vec3{0.05, 1, 1})) == 16);
}

TEST_CASE("DGP under open skies: Ev of a uniform sky and its ground, one source over the "
          "threshold, the sun's disc (#69 item 2)",
          "[sky]") {
    // A speck far behind the eye: the view's hemisphere sees only the sky and the ground.
    std::string obj;
    int n = 0;
    quad_obj(obj, n, {{-100, 0, -0.1}, {-100, 0, 0.1}, {-100, 0.2, 0.1}, {-100, 0.2, -0.1}});
    const auto mesh = black_mesh(obj);
    radfmt::SkyData view;
    view.sky_patches = rad::SkyPatches(1).count();
    view.patch_count = mesh.patches.size();
    view.coefficients.assign(mesh.patches.size() * view.sky_patches * 3, 0.0f);
    const rad::DaylightLuminance luminance(mesh, dark_solution(mesh), view);
    const rad::Vec3 eye{0, 1.5, 0}, look{1, 0, 0};
    // The uniform sky of L over a ground of 0.2 L (0.2 x pi L / pi): Ev = pi/2 (L + 0.2 L).
    const auto dim = luminance.glare(rad::Sky::uniform(2000, rad::SkyFrame{}, 0.2), eye, look);
    CHECK(dim.ev == Approx(0.6 * kPi * 2000).epsilon(0.002));
    CHECK(dim.mean_luminance == Approx(0.6 * 2000).epsilon(0.002));
    CHECK(dim.sources.empty()); // 2000 cd/m^2 does not exceed the threshold of 2000
    CHECK(dim.dgp == Approx(0.159 + 5.87e-5 * dim.ev));
    const auto bright = luminance.glare(rad::Sky::uniform(5000, rad::SkyFrame{}, 0.2), eye, look);
    REQUIRE(bright.sources.size() == 1); // the sky's quarter sphere, one source; the ground not
    CHECK(bright.sources[0].luminance == Approx(5000).epsilon(1e-6));
    CHECK(bright.sources[0].solid_angle == Approx(kPi).epsilon(0.002));
    CHECK(bright.dgp == Approx(rad::daylight_glare_probability(bright.ev, bright.sources, true)));
    // A tenth of the threshold makes it 5 x the mean luminance (evalglare's factor): 3000 cd/m^2
    // at a mean of 3000, so no source.
    rad::GlareOptions factor;
    factor.threshold = 5;
    CHECK(luminance.glare(rad::Sky::uniform(5000, rad::SkyFrame{}, 0.2), eye, look, factor)
              .sources.empty());
    // The clear sky's sun ahead at 20 degrees: its disc is a source of E / (2 pi (1 - cos
    // 0.2665 deg)), and Ev holds its beam x cos 20.
    rad::SunPosition sun;
    sun.zenith = 70;
    sun.azimuth = 90; // east: +X in the default compass
    const auto clear = rad::Sky::clear(sun, rad::SkyFrame{}, 0.2);
    const auto sunny = luminance.glare(clear, eye, look);
    const auto disc = std::find_if(sunny.sources.begin(), sunny.sources.end(),
                                   [](const rad::GlareSource& s) { return s.sun; });
    REQUIRE(disc != sunny.sources.end());
    const double omega = 2 * kPi * (1 - std::cos(0.2665 * kPi / 180));
    CHECK(disc->solid_angle == Approx(omega));
    CHECK(disc->luminance == Approx(clear.sun_normal_illuminance() / omega));
    CHECK(disc->sigma_deg == Approx(20).margin(0.05));
    CHECK(sunny.ev > clear.sun_normal_illuminance() * std::cos(20 * kPi / 180));
    CHECK(sunny.dgp == 1); // the sun in the eye
    // Looking away from it (west), no disc.
    const auto away = luminance.glare(clear, eye, {-1, 0, 0});
    CHECK(std::none_of(away.sources.begin(), away.sources.end(),
                       [](const rad::GlareSource& s) { return s.sun; }));
}

TEST_CASE("EN 17037 by illuminance on a small year worked by hand: per daylight hour, the target "
          "over half of the plane and the minimum over 95% of it (#69 item 3)",
          "[sky]") {
    // 4 points, 5 hours (hour 4 not a daylight hour), one point not on the plane.
    radfmt::AnnualData year;
    year.positions.assign(5, radfmt::Vec3{0, 0, 0});
    year.normals.assign(5, radfmt::Vec3{0, 1, 0});
    year.hours = {10101, 10102, 10103, 10104, 10105};
    year.occupied.assign(5, 1);
    year.sun_lux.assign(25, 0.0f);
    year.lux = {
        300, 300, 100, 100, 9999, // two of four at 300: half; all at 100: minimum over 95%
        299, 300, 500, 99,  9999, // two at 300 (300, 500); one at 99: minimum not over 95%
        750, 750, 500, 500, 0,    // high's target on half, medium's minimum on all
        0,   0,   0,   0,   9999, // dark
        900, 900, 900, 900, 9999, // not a daylight hour
    };
    const std::vector<std::uint8_t> plane{1, 1, 1, 1, 0}, day_hours{1, 1, 1, 1, 0};
    const auto e = rad::en17037_illuminance_method(year, plane, day_hours);
    CHECK(e.daylight_hours == 4);
    CHECK(e.points == 4);
    // minimum (300 / 100 lx): target over half in hours 0, 1, 2 (3 of 4); minimum over 95% in
    // hours 0 and 2 (2 of 4): both at least half, met.
    CHECK(e.levels[0].target_hours == Approx(0.75));
    CHECK(e.levels[0].minimum_hours == Approx(0.5));
    CHECK(e.levels[0].met);
    // medium (500 / 300 lx): target over half only in hour 2; not met.
    CHECK(e.levels[1].target_hours == Approx(0.25));
    CHECK(e.levels[1].minimum_hours == Approx(0.25));
    CHECK_FALSE(e.levels[1].met);
    CHECK(e.levels[2].target_hours == Approx(0.25));  // high: 750 on half in hour 2
    CHECK(e.levels[2].minimum_hours == Approx(0.25)); // 500 on all four in hour 2
    CHECK(e.achieved() == "minimum");
}

TEST_CASE("EN 17037's sunlight exposure: the equinox's hours above 10 degrees at 50 N worked "
          "by hand; a wall to the south hides them all (#69 item 3)",
          "[sky]") {
    // A wall along x (z = 0), 200 m long and 100 m high; north is -Z, so +Z is its south side.
    std::string obj;
    int n = 0;
    quad_obj(obj, n, {{-100, 0, 0}, {100, 0, 0}, {100, 100, 0}, {-100, 100, 0}});
    quad_obj(obj, n, {{-100, 0, 0}, {-100, 100, 0}, {100, 100, 0}, {100, 0, 0}});
    const auto mesh = black_mesh(obj);
    const rad::SunlightScene scene(mesh);
    rad::Location where;
    where.latitude = 50;
    const std::vector<rad::LocalTime> equinox{{2025, 3, 20, 12}};
    // The sun's hours above 10 degrees with declination 0: 2 acos(sin 10 / cos 50) / 15 = 9.91 h
    // (refraction and the day's small declination add a few minutes).
    const auto south = scene.exposure({0, 1, 0.5}, where, rad::SkyFrame{}, equinox, 10);
    CHECK(south.best.hours() == Approx(9.91).margin(0.1));
    CHECK(std::string(south.level()) == "high");
    const auto north = scene.exposure({0, 1, -0.5}, where, rad::SkyFrame{}, equinox, 10);
    CHECK(north.best.minutes == 0);
    CHECK(std::string(north.level()) == "none");
    // EN 17037's days: 1 February to 21 March (49 in 2025, 50 in a leap year).
    CHECK(rad::en17037_sunlight_days(2025).size() == 49);
    CHECK(rad::en17037_sunlight_days(2024).size() == 50);
}
