// The lighting report's parts against hand-worked values: CIE 117's UGR of a luminaire whose
// luminance, solid angle and position index are computed here, EN 12464-1's grid rule, the
// calculation-surfaces file and its refusals, isolines whose every end lies at its level, and
// the figures and verdicts.
#include "helpers.hpp"
#include "radiosity/calc_surfaces.hpp"
#include "radiosity/contours.hpp"
#include "radiosity/glare.hpp"
#include "radiosity/report.hpp"
#include "radiosity/ugr_table.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <tuple>

using namespace testing_helpers;

namespace {
constexpr double kDeg = 180 / std::numbers::pi;

// A 0.6 m x 0.6 m opening giving `candela` in every direction (absolute photometry).
std::string square_panel(double candela) {
    const auto c = std::to_string(candela);
    return "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0.6 0.6 0\n1 1 0\n0 180\n0\n" + c + " " +
           c + "\n";
}

rad::LuminaireSet panels(const std::string& rows, double candela) {
    rad::LuminaireSources sources{
        "layout.csv",
        "name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group\n" + rows,
        {{"panel.ies", square_panel(candela)}}};
    return rad::build_luminaires(sources, 1);
}

// Guth's position index as the IES Lighting Handbook fits it (restated, not the library's).
double guth(double tau, double sigma) {
    return std::exp((35.2 - 0.31889 * tau - 1.22 * std::exp(-2 * tau / 9)) * 1e-3 * sigma +
                    (21 + 0.26667 * tau - 0.002963 * tau * tau) * 1e-5 * sigma * sigma);
}

rad::CalcFile calc_from(const std::string& text) {
    const auto dir = temp_dir("calc");
    write_text(dir / "calc.csv", text);
    return rad::read_calc_file((dir / "calc.csv").string());
}

const std::string kHeader = "name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing,border,Em,U0,Emin,UGRL\n";

// The message read_calc_file gives for `text` (empty when it reads it).
std::string refusal(const std::string& text) {
    try {
        calc_from(text);
    } catch (const rad::InputError& e) {
        return e.what();
    }
    return "";
}
} // namespace

TEST_CASE("UGR of one luminaire equals CIE 117's formula worked by hand") {
    // The eye at 1.2 m looks along -z; the panel is 1.8 m above the eye, 4 m ahead, 1.5 m aside.
    const auto set = panels("P,panel.ies,1.5,3,-4,,,,,1,g\n", 1000);
    const rad::Vec3 eye{0, 1.2, 0}, view{0, 0, -1};
    const double h = 1.8, r = 4, t = 1.5, lb = 10;
    const double distance = std::sqrt(h * h + r * r + t * t);
    const double cos_gamma = h / distance; // the opening faces down
    const double area = 0.36 * cos_gamma, luminance = 1000 / area;
    const double omega = area / (distance * distance);
    const double sigma = std::acos(r / distance) * kDeg, tau = std::atan2(t, h) * kDeg;
    const double p = guth(tau, sigma);
    const double expected = 8 * std::log10(0.25 / lb * luminance * luminance * omega / (p * p));

    const auto glare = rad::observer_glare(set, nullptr, eye, view, lb);
    REQUIRE(glare.terms.size() == 1);
    CHECK(glare.terms[0].luminance == Approx(luminance).epsilon(1e-6));
    CHECK(glare.terms[0].solid_angle == Approx(omega).epsilon(1e-6));
    CHECK(glare.terms[0].sigma_deg == Approx(sigma).epsilon(1e-9));
    CHECK(glare.terms[0].tau_deg == Approx(tau).epsilon(1e-9));
    CHECK(std::abs(glare.ugr - expected) < 0.1);
    CHECK(std::abs(glare.ugr - expected) < 1e-6); // the same formula: to rounding
    // Straight ahead the position index is 1; it grows off the line of sight.
    CHECK(rad::guth_position_index(0, 0) == Approx(1));
    CHECK(rad::guth_position_index(0, 30) > rad::guth_position_index(0, 10));
}

TEST_CASE("UGR counts luminaires in front and above the line of sight, and sums them") {
    const auto set = panels("A,panel.ies,0,3,-3,,,,,1,g\nB,panel.ies,0,3,-6,,,,,1,g\n"
                            "behind,panel.ies,0,3,3,,,,,1,g\nbelow,panel.ies,0,0.5,-3,,,,,1,g\n",
                            2000);
    const auto glare = rad::observer_glare(set, nullptr, {0, 1.2, 0}, {0, 0, -1}, 20);
    REQUIRE(glare.terms.size() == 2);
    CHECK(glare.behind_or_below == 2);
    double sum = 0;
    for (const auto& term : glare.terms) sum += term.contribution();
    CHECK(glare.ugr == Approx(8 * std::log10(0.25 / 20 * sum)));
    // Twice the background lowers UGR by 8 log10(2).
    const auto brighter = rad::observer_glare(set, nullptr, {0, 1.2, 0}, {0, 0, -1}, 40);
    CHECK(glare.ugr - brighter.ugr == Approx(8 * std::log10(2.0)));
    // A luminaire with no luminous opening has no luminance: it is counted apart.
    rad::LuminaireSources point{"layout.csv",
                                "name,photometry,x,y,z\nP,p.ies,0,3,-3\n",
                                {{"p.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n"
                                           "1 1 0\n0 180\n0\n100 100\n"}}};
    const auto pointlike =
        rad::observer_glare(rad::build_luminaires(point, 1), nullptr, {0, 1.2, 0}, {0, 0, -1}, 20);
    CHECK(pointlike.pointlike == 1);
    CHECK(std::isnan(pointlike.ugr));
}

TEST_CASE("UGR leaves out luminaires past CIE 117's position-index table instead of capping p") {
    // The eye at 1.2 m looks along -z. X lies 77 degrees off the line of sight and 66 degrees
    // above the horizontal, 0.7 m away: H/R = 4.06, past the table's 1.9.
    const double sigma = 77 / kDeg, elevation = 66 / kDeg, d = 0.7;
    const double ahead = std::cos(sigma), above = std::sin(elevation);
    const double across = std::sqrt(1 - ahead * ahead - above * above);
    const rad::Vec3 eye{0, 1.2, 0}, view{0, 0, -1};
    const rad::Vec3 x{across * d, 1.2 + above * d, -ahead * d};
    char rows[200];
    std::snprintf(rows, sizeof rows,
                  "A,panel.ies,1,3,-5,,,,,1,g\nX,panel.ies,%.9f,%.9f,%.9f,,,,,1,g\n", x[0], x[1],
                  x[2]);
    const auto set = panels(rows, 1000);
    const auto glare = rad::observer_glare(set, nullptr, eye, view, 10);
    REQUIRE(glare.terms.size() == 1);
    CHECK(set.luminaires[glare.terms[0].luminaire].name == "A");
    REQUIRE(glare.outside_table.size() == 1);
    CHECK(set.luminaires[glare.outside_table[0]].name == "X");
    CHECK(glare.ugr == Approx(8 * std::log10(0.25 / 10 * glare.terms[0].contribution())));
    // Capped at 16 as before, X would have added a term of its own (the room: 97% of
    // the sum, 19.4 where the rule gives 6.7).
    const double area = 0.36 * above, luminance = 1000 / area; // its opening faces down
    const double x_term = luminance * luminance * (area / (d * d)) / (16.0 * 16.0);
    const double capped = 8 * std::log10(0.25 / 10 * (x_term + glare.terms[0].contribution()));
    CHECK(capped - glare.ugr > 0.5);
    // The table's edges: H/R 1.8 and T/R 2.9 count, 2.0 and 3.1 do not (R = 1 m ahead).
    const auto edges =
        panels("h18,panel.ies,0,3.0,-1,,,,,1,g\nh20,panel.ies,0,3.2,-1,,,,,1,g\n"
               "t29,panel.ies,2.9,1.3,-1,,,,,1,g\nt31,panel.ies,3.1,1.3,-1,,,,,1,g\n",
               1000);
    const auto edge = rad::observer_glare(edges, nullptr, eye, view, 10);
    std::vector<std::string> counted, left_out;
    for (const auto& t : edge.terms) counted.push_back(edges.luminaires[t.luminaire].name);
    for (const auto k : edge.outside_table) left_out.push_back(edges.luminaires[k].name);
    CHECK(counted == std::vector<std::string>{"h18", "t29"});
    CHECK(left_out == std::vector<std::string>{"h20", "t31"});
}

TEST_CASE("UGR over a grid of luminaires equals CIE 117's sum worked here") {
    // A room 8 m x 8 m, panels 1.8 m above the eye at 2 m spacing, the eye at a wall's middle
    // looking across: the sum over the table's extent, each term restated from H, R and T.
    std::string rows;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            char row[80];
            std::snprintf(row, sizeof row, "P%d%d,panel.ies,%d,3,%g,,,,,1,g\n", i, j, -3 + 2 * i,
                          -0.5 - 2 * j);
            rows += row;
        }
    const auto set = panels(rows, 2500);
    const rad::Vec3 eye{0, 1.2, 0}, view{0, 0, -1};
    const double lb = 25;
    double sum = 0;
    int counted = 0, left_out = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const double t = std::abs(-3.0 + 2 * i), r = 0.5 + 2 * j, h = 1.8;
            if (h / r > 1.9 || t / r > 3.0) {
                ++left_out;
                continue;
            }
            const double dist = std::sqrt(h * h + r * r + t * t);
            const double area = 0.36 * h / dist, luminance = 2500 / area;
            const double p = guth(std::atan2(t, h) * kDeg, std::acos(r / dist) * kDeg);
            sum += luminance * luminance * (area / (dist * dist)) / (p * p);
            ++counted;
        }
    const auto glare = rad::observer_glare(set, nullptr, eye, view, lb);
    CHECK(glare.terms.size() == static_cast<std::size_t>(counted));
    CHECK(glare.outside_table.size() == static_cast<std::size_t>(left_out));
    CHECK(left_out == 4); // the nearest row (R = 0.5 m: H/R = 3.6) is past the table
    CHECK(glare.ugr == Approx(8 * std::log10(0.25 / lb * sum)).epsilon(1e-9));
}

TEST_CASE("EN 12464-1's grid: p = 0.2 x 5^log10(d), at most 10 m, the border band left out") {
    CHECK(rad::en12464_spacing(1) == Approx(0.2));
    CHECK(rad::en12464_spacing(10) == Approx(1.0));
    CHECK(rad::en12464_spacing(100) == Approx(5.0));
    CHECK(rad::en12464_spacing(1000) == Approx(10.0));
    const auto file = calc_from(kHeader + "wp,workplane,0,0.8,4,6,0,0,0,0,-4,,,500,0.6,,\n"
                                          "wall,wall,0,0,0,6,0,0,0,3,0,0.5,,,,,\n");
    const auto wp = rad::surface_grid(file.surfaces[0], 1);
    CHECK(wp.border_m == 0.5);
    CHECK(wp.width_m == Approx(5));
    CHECK(wp.depth_m == Approx(3));
    CHECK(wp.spacing_m == Approx(0.2 * std::pow(5, std::log10(5.0))));
    CHECK(wp.columns == 9); // ceil(5 / 0.616)
    CHECK(wp.rows == 5);    // ceil(3 / 0.616)
    CHECK(wp.normal[1] == Approx(1));
    // The first sensor: half a cell in from the calculation area's corner (0.5, 0.8, 3.5).
    const auto first = wp.position(0);
    CHECK(first[0] == Approx(0.5 + 5.0 / 9 / 2));
    CHECK(first[2] == Approx(3.5 - 3.0 / 5 / 2));
    CHECK(wp.position(9)[2] == Approx(3.5 - 3.0 / 5 * 1.5)); // the next row
    const auto wall = rad::surface_grid(file.surfaces[1], 1);
    CHECK(wall.border_m == 0);
    CHECK(wall.columns == 12);
    CHECK(wall.rows == 6);
    CHECK(wall.normal[2] == Approx(1)); // out of the wall at z = 0, into the room
    // In centimetres the same room gives the same grid.
    const auto cm = calc_from(kHeader + "wp,workplane,0,80,400,600,0,0,0,0,-400,,,,,,\n");
    const auto wp_cm = rad::surface_grid(cm.surfaces[0], 0.01);
    CHECK(wp_cm.columns == 9);
    CHECK(wp_cm.position(0)[0] == Approx(100 * first[0]));
}

TEST_CASE("the calculation-surfaces file is refused with its line and the fix") {
    CHECK(refusal(kHeader + "a,shelf,0,0,0,1,0,0,0,0,-1,,,,,,\n").find("calc.csv:2: kind") !=
          std::string::npos);
    CHECK(refusal(kHeader + "a,,0,0,0,1,0,0,0,0,-1,,,,,,\na,,0,0,0,1,0,0,0,0,-1,,,,,,\n")
              .find("calc.csv:3: 'a' is named twice") != std::string::npos);
    CHECK(refusal(kHeader + "a,,0,0,0,1,0,0,2,0,0,,,,,,\n").find("span no area") !=
          std::string::npos);
    CHECK(refusal(kHeader + "a,,0,0,0,1,0,0,0,0,-1,,,,1.5,,\n").find("U0 is Emin/Em") !=
          std::string::npos);
    CHECK(refusal(kHeader + "a,,0,0,0,1,0,0,0,0,-1,,,x,,,\n").find("Em is 'x', not a number") !=
          std::string::npos);
    CHECK(refusal(kHeader + "o,observer,0,1,0,0,0,-1,,,,,,300,,,\n").find("no Em") !=
          std::string::npos);
    CHECK(refusal("name,kind,x,y,z,ux,uy,uz,DF\no,observer,0,1,0,0,0,-1,2\n").find("no DF") !=
          std::string::npos);
    CHECK(refusal("name,x,y,z,ux,uy,uz,vx,vy,vz,sDA\na,0,0,0,1,0,0,0,0,-1,120\n")
              .find("sDA is a share") != std::string::npos);
    CHECK(refusal(kHeader + "o,observer,0,1,0,0,0,0,,,,,,,,,\n").find("line of sight") !=
          std::string::npos);
    CHECK(refusal(kHeader + "c,camera,0,1,0,0,0,-1,0,0,-2,,,,,,\n").find("along its direction") !=
          std::string::npos);
    CHECK(refusal("name,kind,x,y,z,ux,uy,uz,angle\nc,camera,0,1,0,0,0,-1,200\n").find("angle is") !=
          std::string::npos);
    CHECK(refusal("name,kind,x,y,z,ux,uy,uz,vx,vy,vz,angle\nc,,0,1,0,1,0,0,0,0,-1,20\n")
              .find("angle is an") != std::string::npos);
    const auto camera = calc_from("name,kind,x,y,z,ux,uy,uz,angle\nc,camera,0,1,0,0,0,-2,90\n");
    REQUIRE(camera.cameras.size() == 1);
    CHECK(camera.cameras[0].direction[2] == Approx(-1));
    CHECK(camera.cameras[0].up[1] == 1);
    CHECK(camera.cameras[0].angle_deg == 90);
    CHECK(refusal("x,y,z\n").find("calc.csv:1: the first line names the columns") !=
          std::string::npos);
    CHECK(refusal("name,x,y,z,ux,uy,uz,colour\n").find("unknown column 'colour'") !=
          std::string::npos);
    CHECK(refusal(kHeader).find("no surface, observer or camera") != std::string::npos);
    // A border that leaves nothing is refused when the grid is made, at the surface's line.
    const auto small = calc_from(kHeader + "# a comment\n\ntiny,,0,0,0,0.8,0,0,0,0,-3,,,,,,\n");
    REQUIRE_THROWS_WITH(rad::surface_grid(small.surfaces[0], 1),
                        Catch::Contains("calc.csv:4: the border band"));
    // A name with a comma and quotes, quoted in the file, reads back as written out.
    const std::string name = "bay \"A\", east";
    const auto quoted =
        calc_from(kHeader + rad::csv_field(name) + ",task,0,0,0,1,0,0,0,0,-1,,,,,,\n");
    CHECK(quoted.surfaces[0].name == name);
    CHECK(quoted.surfaces[0].kind == rad::CalcKind::Task);
    // As spreadsheets write them (#70 item 11): a cell holding a line break is quoted over
    // two lines, one record, refused for what is wrong with it at its first line (it was
    // two rows: "x is empty"); a quote never closed is said as such; a name that is not UTF-8
    // (bytes FF FE) is refused before it reaches a page declared UTF-8.
    CHECK(refusal(kHeader + "\"bay\nA\",task,0,0,0,1,0,0,0,0,-1,,,,,,\n")
              .find("calc.csv:2: 'bay?A' is a name holding a control character") !=
          std::string::npos);
    CHECK(refusal(kHeader +
                  "a,\"task\n\",0,0,0,1,0,0,0,0,-1,,,,,,\nb,task,0,0,0,1,0,0,0,0,-1,,,,,,\n")
              .find("calc.csv:2: kind is") != std::string::npos);
    CHECK(refusal(kHeader + "a,task,0,0,0,1,0,0,0,0,-1,,,,,,\n\"b,task,0,0,0,1,0,0,0,0,-1,,,,,,\n")
              .find("calc.csv:3: a double quote opened on this line is never closed") !=
          std::string::npos);
    CHECK(refusal(kHeader + "\xFF\xFE"
                            "bay,task,0,0,0,1,0,0,0,0,-1,,,,,,\n")
              .find("not UTF-8") != std::string::npos);
    // A quoted name with a comma over one line, then the next row, still reads.
    const auto two = calc_from(kHeader + "\"a, \"\"1\"\"\",task,0,0,0,1,0,0,0,0,-1,,,,,,\n" +
                               "b,task,0,0,0,1,0,0,0,0,-1,,,,,,\n");
    CHECK(two.surfaces.size() == 2);
}

TEST_CASE(
    "every end of an isoline lies where the values, linear between sensors, equal its level") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(0, 100);
    const long columns = 13, rows = 9;
    std::vector<double> grid(columns * rows);
    for (auto& v : grid) v = value(rng);
    grid[20] = std::nan(""); // a sensor without a value: no line through its squares
    // An end lies on a square's edge: the values linear along that edge.
    const auto at = [&](double x, double y) {
        const auto v = [&](long c, long r) { return grid[std::size_t(r * columns + c)]; };
        if (x == std::floor(x)) {
            const long r = std::min(long(std::floor(y)), rows - 2);
            return v(long(x), r) + (y - double(r)) * (v(long(x), r + 1) - v(long(x), r));
        }
        const long c = std::min(long(std::floor(x)), columns - 2);
        return v(c, long(y)) + (x - double(c)) * (v(c + 1, long(y)) - v(c, long(y)));
    };
    long ends = 0;
    for (const double level : {20.0, 50.0, 75.0}) {
        const auto segments = rad::isolines(grid, columns, rows, level);
        CHECK(!segments.empty());
        for (const auto& s : segments) {
            for (const auto& [x, y] : {std::pair{s.x0, s.y0}, std::pair{s.x1, s.y1}}) {
                const bool on_edge = x == std::floor(x) || y == std::floor(y);
                CHECK(on_edge);
                CHECK(at(x, y) == Approx(level).epsilon(1e-9));
                CHECK(std::hypot(x - 20 % columns, y - 20 / columns) >= 1 - 1e-12);
                ++ends;
            }
        }
    }
    CHECK(ends > 50);
    // A saddle: two pieces.
    const std::vector<double> saddle{1, 0, 0, 1};
    CHECK(rad::isolines(saddle, 2, 2, 0.5).size() == 2);
    CHECK(rad::isolines(saddle, 2, 2, 2).empty());
    // Round levels inside the range.
    CHECK(rad::contour_levels(85.5, 145) == std::vector<double>{90, 100, 110, 120, 130, 140});
    CHECK(rad::contour_levels(23.5, 27.5) == std::vector<double>{24, 25, 26, 27});
    CHECK(rad::contour_levels(5, 5).empty());
}

TEST_CASE("a surface's figures leave out sensors without a value, and its verdict follows them") {
    const std::vector<double> lux{400, 600, std::nan(""), 500};
    const auto stats = rad::illuminance_stats(lux);
    CHECK(stats.count == 3);
    CHECK(stats.without_value == 1);
    CHECK(stats.mean == Approx(500));
    CHECK(stats.u0() == Approx(0.8));
    CHECK(stats.min_over_max() == Approx(400.0 / 600));
    const std::vector<double> none{std::nan(""), std::nan("")}; // every sensor inside furniture
    const auto empty = rad::illuminance_stats(none);
    CHECK(empty.without_value == 2);
    CHECK(rad::lux_text(empty.mean) == "-");
    CHECK(rad::ratio_text(empty.u0()) == "-");
    rad::Requirements em;
    em.em = 1;
    CHECK(!rad::judge(empty, em).passes()); // no value meets no requirement
    rad::Requirements required;
    CHECK(rad::judge(stats, required).passes()); // nothing required
    required.em = 500, required.u0 = 0.6;
    CHECK(rad::judge(stats, required).passes());
    required.emin = 450;
    CHECK(!rad::judge(stats, required).passes());
    CHECK(!rad::judge(stats, required).emin);
    rad::Requirements day;
    CHECK(rad::judge_daylight(1.5, nullptr, nullptr, day).passes());
    day.df = 2, day.sda = 55, day.ase = 10;
    CHECK(!rad::judge_daylight(1.5, nullptr, nullptr, day).passes()); // DF 1.5% < 2%
    const double sda = 0.6, ase = 0.05, ase_high = 0.4;
    CHECK(rad::judge_daylight(2, &sda, &ase, day).passes());
    CHECK(!rad::judge_daylight(2, &sda, &ase_high, day).ase);      // 40% > 10%
    CHECK(rad::judge_daylight(2, nullptr, nullptr, day).passes()); // no year: not judged
    CHECK(rad::lux_text(412.4) == "412");
    CHECK(rad::lux_text(41.24) == "41.2");
    CHECK(rad::lux_text(4.124) == "4.12");
    CHECK(rad::lux_text(std::nan("")) == "-");
    CHECK(rad::html_escape("<a & \"b\">") == "&lt;a &amp; &quot;b&quot;&gt;");
}

TEST_CASE("a figure printed beside its requirement agrees with the verdict") {
    // #68: U0 0.5995 was printed "0.60" beside "fails 0.60".
    CHECK(rad::ratio_text(0.5995, 0.6) == "0.5995");
    CHECK(rad::ratio_text(0.59951, 0.6) == "0.5995");
    CHECK(rad::ratio_text(0.6001, 0.6) == "0.60");
    CHECK(rad::ratio_text(0.5912, 0.6) == "0.59");
    CHECK(rad::ratio_text(0.5995, std::nan("")) == "0.60"); // nothing asked: two decimals
    CHECK(rad::lux_text(499.6, 500) == "499.6");
    CHECK(rad::lux_text(499.96, 500) == "499.96");
    CHECK(rad::lux_text(500.4, 500) == "500");
    CHECK(rad::lux_text(412.3, 500) == "412");
}

TEST_CASE("LENI by EN 15193-1's quick method equals its formula worked by hand") {
    // A school: 1800 h with daylight, 200 without; constant illuminance (0.9), automatic
    // daylight control (0.7), 3 W of standby, 5 W charging 4000 h; 800 W over 100 m^2.
    const auto in = rad::parse_lighting_energy("education,FC=0.9,FD=0.7,Ppc=3,Pem=5,te=4000");
    CHECK(in.daylight_hours == 1800);
    CHECK(in.night_hours == 200);
    CHECK(in.given == std::vector<std::string>{"FC", "FD", "Ppc", "Pem", "te"});
    const auto e = rad::lighting_energy(in, 800, 100);
    // W_L = 800 x 0.9 x (1800 x 1 x 0.7 + 200 x 1) / 1000 = 1051.2 kWh
    CHECK(e.lighting_kwh == Approx(1051.2).epsilon(1e-12));
    // W_P = (3 x (8760 - 2000) + 5 x 4000) / 1000 = 40.28 kWh
    CHECK(e.parasitic_kwh == Approx(40.28).epsilon(1e-12));
    CHECK(e.leni() == Approx(10.9148).epsilon(1e-12));
    // Hours given replace the building's; every type has its hours.
    CHECK(rad::parse_lighting_energy("hotel,tD=1000,tN=500").night_hours == 500);
    for (const auto& b : rad::lighting_energy_buildings()) {
        const auto hours = rad::parse_lighting_energy(b);
        CHECK(hours.daylight_hours + hours.night_hours > 0);
        CHECK(hours.daylight_hours + hours.night_hours <= rad::kHoursInYear);
    }
    CHECK_THROWS_WITH(rad::parse_lighting_energy("office,tD=8000,tN=1000"),
                      Catch::Contains("more than the year's 8760 hours"));
    CHECK_THROWS_WITH(rad::parse_lighting_energy("office,FO=-1"),
                      Catch::Contains("FO=-1 is not a number of 0 or more"));
    CHECK_THROWS_WITH(rad::parse_lighting_energy("office,FO"), Catch::Contains("is not KEY=VALUE"));
    CHECK_THROWS_WITH(rad::lighting_energy(in, 0, 100), Catch::Contains("input power is unknown"));
    CHECK_THROWS_WITH(rad::lighting_energy(in, 800, 0), Catch::Contains("give --area"));
}

TEST_CASE("walls and ceilings get EN 12464-1's minimum, escape routes EN 1838's, unless given") {
    const std::string header = "name,kind,x,y,z,ux,uy,uz,vx,vy,vz,Em,U0,Emin\n";
    const auto file =
        calc_from(header + "w,wall,0,0,0,6,0,0,0,3,0,,,\n" + "c,ceiling,0,3,0,6,0,0,0,0,4,,,\n" +
                  "w2,wall,0,0,4,6,0,0,0,3,0,75,0.2,\n" + "f,floor,0,0,0,6,0,0,0,0,-4,,,\n" +
                  "r,escape-route,0,0,2,6,0,0,0,0,-2,,,\n" + "a,open-area,0,0,2,6,0,0,0,0,-2,,,\n" +
                  "z,cylindrical,0,1.2,4,6,0,0,0,0,-4,150,0.1,\n");
    const auto& s = file.surfaces;
    REQUIRE(s.size() == 7);
    CHECK(s[0].required.em == 50);
    CHECK(s[0].required.u0 == 0.1);
    CHECK(s[1].required.em == 30);
    CHECK(s[1].required.u0 == 0.1);
    CHECK(s[2].required.em == 75);
    CHECK(s[2].required.u0 == 0.2);
    CHECK(!s[3].required.of_light());
    CHECK(s[4].required.emin == 1);
    CHECK(s[4].required.max_over_min == 40);
    CHECK(s[5].required.emin == 0.5);
    CHECK(s[6].required.em == 150);
    // An escape route's sensors lie on its centre line, 0.25 m apart at most.
    const auto route = rad::surface_grid(s[4], 1);
    CHECK(route.rows == 1);
    CHECK(route.columns == 24);
    CHECK(route.position(0)[2] == Approx(1));
    CHECK(route.emergency);
    // An open area leaves its 0.5 m band out; a cylindrical area too.
    CHECK(rad::surface_grid(s[5], 1).width_m == Approx(5));
    CHECK(rad::surface_grid(s[6], 1).depth_m == Approx(3));
    CHECK(rad::surface_grid(s[6], 1).cylindrical);
    // Emax/Emin over 40 fails; a minimum of 0 never meets it.
    rad::IlluminanceStats stats;
    stats.count = 2, stats.min = 1, stats.max = 41, stats.mean = 21;
    CHECK_FALSE(rad::judge(stats, s[4].required).passes());
    stats.max = 39, stats.mean = 20;
    CHECK(rad::judge(stats, s[4].required).passes());
}

TEST_CASE("a plan cuts the room at its plane: walls, a cabinet and a glazed partition") {
    // A 6 x 3 x 4 m room, a cabinet 1 x 1.6 x 0.5 m standing free, a glazed partition 2 m long
    // from the floor to 2.5 m; a work plane at 0.8 m over the whole room (0.5 m border). Cut
    // there: the walls 20 m, the cabinet's four sides 3 m, the glass 2 m (drawn as glazing).
    auto quad = [](std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c,
                   std::array<double, 3> d) {
        std::string out;
        for (const auto& p : {a, b, c, d})
            out += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " +
                   std::to_string(p[2]) + "\n";
        return out + "f -4 -3 -2 -1\n";
    };
    std::string obj = "usemtl grey\n";
    obj += quad({0, 0, 0}, {6, 0, 0}, {6, 3, 0}, {0, 3, 0});
    obj += quad({0, 0, 4}, {0, 3, 4}, {6, 3, 4}, {6, 0, 4});
    obj += quad({0, 0, 0}, {0, 3, 0}, {0, 3, 4}, {0, 0, 4});
    obj += quad({6, 0, 0}, {6, 0, 4}, {6, 3, 4}, {6, 3, 0});
    obj += quad({0, 0, 0}, {0, 0, 4}, {6, 0, 4}, {6, 0, 0});
    obj += quad({1, 0, 1}, {2, 0, 1}, {2, 1.6, 1}, {1, 1.6, 1});
    obj += quad({1, 0, 1.5}, {1, 1.6, 1.5}, {2, 1.6, 1.5}, {2, 0, 1.5});
    obj += quad({1, 0, 1}, {1, 1.6, 1}, {1, 1.6, 1.5}, {1, 0, 1.5});
    obj += quad({2, 0, 1}, {2, 0, 1.5}, {2, 1.6, 1.5}, {2, 1.6, 1});
    obj += quad({1, 1.6, 1}, {2, 1.6, 1}, {2, 1.6, 1.5}, {1, 1.6, 1.5});
    obj += "usemtl glass\n" + quad({4, 0, 1}, {4, 2.5, 1}, {4, 2.5, 3}, {4, 0, 3});
    rad::SubdivisionOptions options;
    options.max_edge = 0.5;
    const auto mesh = rad::subdivide(
        scene_from_obj(obj, "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl glass\nKd 0.05 0.05 0.05\nd 0.2\n",
                       "plan_cut"),
        options);
    const auto file = calc_from(kHeader + "wp,workplane,0,0.8,4,6,0,0,0,0,-4,,0.5,500,,,\n");
    rad::ReportSurface s;
    s.surface = file.surfaces[0];
    s.grid = rad::surface_grid(s.surface, 1);
    s.cut = rad::plan_cut(mesh, s.grid, 1);
    double solid = 0, glass = 0;
    for (const auto& c : s.cut) {
        const double length = std::hypot(c.u1 - c.u0, c.v1 - c.v0);
        (c.glass ? glass : solid) += length;
        // Within the surface and its border (u, v from the calculation area's corner).
        for (const double u : {c.u0, c.u1}) CHECK((u >= -0.501 && u <= 5.501));
        for (const double v : {c.v0, c.v1}) CHECK((v >= -0.501 && v <= 3.501));
    }
    CHECK(solid == Approx(23).epsilon(1e-6));
    CHECK(glass == Approx(2).epsilon(1e-6));
    // The glass runs along v at x = 4: u = 3.5 on the plan, v from z = 3 to z = 1 (0.5 to 2.5).
    for (const auto& c : s.cut)
        if (c.glass) {
            CHECK(c.u0 == Approx(3.5));
            CHECK(c.u1 == Approx(3.5));
        }
    // On the plan: the cut drawn, north where it lies (u is +x, v is -z, up the page).
    s.lux.assign(std::size_t(s.grid.size()), 500.0);
    const auto attribute = [](const std::string& svg, const std::string& name) {
        const auto at = svg.find(name + "=\"");
        REQUIRE(at != std::string::npos);
        return std::stod(svg.substr(at + name.size() + 2));
    };
    for (const auto& [north, dx, dy] : {std::tuple{0.0, 0.0, -1.0}, std::tuple{90.0, 1.0, 0.0},
                                        std::tuple{-45.0, -0.7071, -0.7071}}) {
        CAPTURE(north);
        const auto svg =
            rad::surface_plan_svg(s, s.lux, {"lux", "lx", 0, 540, 400, north}, nullptr, 1);
        CHECK(svg.find("class=\"cut\"") != std::string::npos);
        CHECK(svg.find("class=\"cut-glass\"") != std::string::npos);
        CHECK(attribute(svg, "data-dx") == Approx(dx).margin(1e-3));
        CHECK(attribute(svg, "data-dy") == Approx(dy).margin(1e-3));
    }
    const auto unknown = rad::surface_plan_svg(s, s.lux, {"lux", "lx", 0}, nullptr, 1);
    CHECK(unknown.find("class=\"north\"") == std::string::npos);
    // A wall is not cut, nor given north.
    const auto wall_file = calc_from(kHeader + "wall,wall,0,0,0,6,0,0,0,3,0,0.5,,,,,\n");
    CHECK(rad::plan_cut(mesh, rad::surface_grid(wall_file.surfaces[0], 1), 1).empty());
}

// CIE 190's tabular UGR (#68 item 4): the room's transfer of first flux to indirect wall light
// against CIE 190's Table 5 (as eulumdat-ugr's background.py transcribes it, at its commit
// 9f601474), and where the luminaires' light first lands against the definition summed here
// over the standard room's own 0.25 H grid, luminaire by luminaire, over the floor.
TEST_CASE("CIE 190's wall transfer factors are the three-surface room's exchange") {
    struct Row {
        int across, along;
        rad::RoomReflectances rho;
        double fw, ww, cw; // Table 5: F_T,FW, F_T,WW - 1, F_T,CW
    };
    const Row rows[] = {{2, 2, {0.7, 0.5, 0.2}, 0.220, 0.422, 0.646},
                        {4, 8, {0.7, 0.5, 0.2}, 0.115, 0.211, 0.307},
                        {4, 8, {0.3, 0.3, 0.2}, 0.081, 0.092, 0.114},
                        {8, 8, {0.7, 0.5, 0.2}, 0.083, 0.155, 0.215},
                        {12, 8, {0.3, 0.3, 0.2}, 0.049, 0.059, 0.069},
                        {2, 12, {0.7, 0.3, 0.2}, 0.143, 0.156, 0.397}};
    for (const auto& r : rows) {
        const auto t = rad::wall_transfer(r.across, r.along, r.rho);
        INFO(r.across << "H x " << r.along << "H");
        CHECK(t.from_floor == Approx(r.fw).margin(6e-4));
        CHECK(t.from_walls == Approx(r.ww).margin(6e-4));
        CHECK(t.from_ceiling == Approx(r.cw).margin(6e-4));
    }
    // Black surfaces pass nothing on; and the room is symmetric in its two sides.
    const auto black = rad::wall_transfer(4, 8, {0, 0, 0});
    CHECK(black.from_floor == 0);
    CHECK(black.from_ceiling == 0);
    const auto turned = rad::wall_transfer(8, 4, {0.7, 0.5, 0.2});
    CHECK(turned.from_floor == Approx(rows[1].fw).margin(6e-4));
}

TEST_CASE("the light first landing on the reference plane is the grid's own, luminaire by "
          "luminaire") {
    const auto path =
        fs::path(RADIOSITY_SOURCE_DIR) / "tests/data/photometry/eulumdat-ugr_sample_01_Isym4.ldt";
    const auto p = rad::read_photometry_file(path);
    rad::LuminaireSet set;
    set.photometries = {p};
    set.photometry_flux = {p.flux()};
    for (const auto room : {rad::UgrRoom{2, 2}, rad::UgrRoom{4, 8}, rad::UgrRoom{8, 4}}) {
        // By definition: every luminaire of the 0.25 H grid (H = 2 m), its illuminance
        // I cos(gamma) / d^2 summed over the floor in 5 cm cells, over the lamps' flux.
        const double along = room.along * 2.0, across = room.across * 2.0, s = 0.5, cell = 0.05;
        double on_floor = 0;
        rad::Luminaire l; // crosswise: C0 along the line of sight (+X)
        for (double lx = s / 2; lx < along; lx += s)
            for (double lz = s / 2; lz < across; lz += s)
                for (double x = cell / 2; x < along; x += cell)
                    for (double z = cell / 2; z < across; z += cell) {
                        const rad::Vec3 d{x - lx, -2.0, z - lz};
                        const double r2 = rad::dot(d, d), r = std::sqrt(r2);
                        on_floor +=
                            set.intensity(l, rad::normalized(d)) * (2.0 / r) / r2 * cell * cell;
                    }
        const double luminaires = (along / s) * (across / s);
        const double expected = on_floor / (luminaires * p.lamp_lumens);
        const auto first = rad::standard_room_first_flux(p, room, rad::UgrView::crosswise);
        INFO(room.across << "H x " << room.along << "H: the grid gives " << expected);
        CHECK(first.floor == Approx(expected).margin(0.006));
        CHECK(first.floor + first.walls == Approx(p.downward_flux() / p.lamp_lumens).margin(2e-3));
        CHECK(first.ceiling == Approx((p.flux() - p.downward_flux()) / p.lamp_lumens).margin(2e-3));
    }
}

TEST_CASE("a UGR table needs a luminous opening and scales with the flux as CIE 190's eq. 2") {
    const auto dir = temp_dir("ugr-table");
    write_text(dir / "point.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 "
                                  "0\n0 90\n0\n300 0\n");
    CHECK_THROWS_WITH(rad::ugr_table(rad::read_photometry_file(dir / "point.ies")),
                      Catch::Contains("point.ies") && Catch::Contains("luminous opening"));
    // The same panel with twice the lamp flux (and so twice the candela): every value
    // 8 log10(2) higher.
    auto panel = [&](const char* name, const char* lumens_and_multiplier) {
        write_text(dir / name, std::string("IESNA:LM-63-2002\nTILT=NONE\n1 ") +
                                   lumens_and_multiplier +
                                   " 3 1 1 2 0.6 0.6 0\n1 1 0\n0 45 90\n0\n300 212 0\n");
        return rad::ugr_table(rad::read_photometry_file(dir / name));
    };
    const auto one = panel("one.ies", "1000 1");
    const auto two = panel("two.ies", "2000 2");
    CHECK(two.lamp_flux == 2000);
    for (std::size_t r = 0; r < rad::kUgrTableRooms.size(); ++r)
        for (int c = 0; c < 10; ++c)
            CHECK(two.ugr[r][c] - one.ugr[r][c] == Approx(8 * std::log10(2.0)).margin(1e-9));
}
