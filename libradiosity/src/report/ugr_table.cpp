// CIE 190:2010's tabular UGR of a luminaire type: CIE 117's sum over the standard room's grid
// of luminaires, over CIE 190's background luminance. (radiosity/ugr_table.hpp)
#include "radiosity/ugr_table.hpp"

#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/glare.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/report.hpp"
#include "report/number_text.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace rad {
namespace {

constexpr double kHeight = 2.0;                         // m, the luminaires' plane above the eye
constexpr double kSpacing = 0.25 * kHeight;             // m, CIE 117's spacing for the tables
constexpr double kGammaStep = 0.25, kAzimuthStep = 1.0; // degrees, the flux quadrature

// The luminaire's frame in the standard room: the eye at the origin looking along +X, the
// vertical +Y, X (across the line of sight) along Z.
Luminaire standard_luminaire(UgrView view) {
    Luminaire l;
    l.nadir = {0, -1, 0};
    if (view == UgrView::crosswise) {
        l.c0 = {1, 0, 0}; // the line of sight in the C0-C180 plane
        l.c90 = {0, 0, -1};
    } else {
        l.c0 = {0, 0, 1}; // in the C90-C270 plane (c0 x c90 stays up, as the default frame)
        l.c90 = {1, 0, 0};
    }
    return l;
}

LuminaireSet single_type(const Photometry& photometry) {
    LuminaireSet set;
    set.photometries = {photometry};
    set.photometry_flux = {photometry.flux()};
    set.groups = {"table"};
    return set;
}

double lamp_flux_of(const Photometry& photometry) {
    return photometry.lamp_lumens > 0 ? photometry.lamp_lumens : photometry.flux();
}

// A direction below the horizon: its share of the lamp flux, and where it lands on the
// reference plane per unit drop (along and across the line of sight).
struct DownwardRay {
    double share = 0, along = 0, across = 0;
};

// The lamp flux's directions below the horizon (midpoint rule in gamma and azimuth) and the
// upward share.
std::vector<DownwardRay> downward_rays(const Photometry& photometry, UgrView view,
                                       double* upward_share) {
    const LuminaireSet set = single_type(photometry);
    const Luminaire l = standard_luminaire(view);
    const double lamp_flux = lamp_flux_of(photometry);
    constexpr double kRad = std::numbers::pi / 180;
    const int gammas = static_cast<int>(180 / kGammaStep);
    const int azimuths = static_cast<int>(360 / kAzimuthStep);
    std::vector<DownwardRay> rays;
    double upward = 0;
    for (int i = 0; i < gammas; ++i) {
        const double gamma = (i + 0.5) * kGammaStep * kRad;
        const double solid_angle = std::sin(gamma) * kGammaStep * kRad * kAzimuthStep * kRad;
        for (int j = 0; j < azimuths; ++j) {
            const double phi = (j + 0.5) * kAzimuthStep * kRad;
            const Vec3 d{std::sin(gamma) * std::cos(phi), -std::cos(gamma),
                         std::sin(gamma) * std::sin(phi)};
            const double share = set.intensity(l, d) * solid_angle / lamp_flux;
            if (d[1] >= 0) {
                upward += share;
                continue;
            }
            rays.push_back({share, d[0] / -d[1], d[2] / -d[1]});
        }
    }
    *upward_share = upward;
    return rays;
}

FirstFlux first_flux(const std::vector<DownwardRay>& rays, double upward, const UgrRoom& room) {
    const double along = room.along * kHeight, across = room.across * kHeight;
    FirstFlux f;
    double downward = 0;
    for (const auto& r : rays) {
        downward += r.share;
        // The share of the grid's positions from which this ray lands inside the room.
        const double inside_along = std::max(0.0, 1 - std::abs(r.along) * kHeight / along);
        const double inside_across = std::max(0.0, 1 - std::abs(r.across) * kHeight / across);
        f.floor += r.share * inside_along * inside_across;
    }
    f.walls = downward - f.floor;
    f.ceiling = upward;
    return f;
}

// Solves the 3 x 3 system a x = b (Cramer's rule: the matrix is well conditioned, I - rho F).
std::array<double, 3> solve3(const std::array<std::array<double, 3>, 3>& a,
                             const std::array<double, 3>& b) {
    auto det = [](const std::array<std::array<double, 3>, 3>& m) {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double d = det(a);
    std::array<double, 3> x{};
    for (int k = 0; k < 3; ++k) {
        auto m = a;
        for (int r = 0; r < 3; ++r) m[r][k] = b[r];
        x[k] = det(m) / d;
    }
    return x;
}

// CIE 117's sum of L^2 omega / p^2 over the room's 0.25 H grid, for an observer at the middle
// of the wall it faces; and the luminaires in the grid.
double glare_sum(const Photometry& photometry, const UgrRoom& room, UgrView view,
                 long* luminaires) {
    LuminaireSet set = single_type(photometry);
    const int rows = static_cast<int>(std::lround(room.along * kHeight / kSpacing));
    const int columns = static_cast<int>(std::lround(room.across * kHeight / kSpacing));
    const double half_width = room.across * kHeight / 2;
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < columns; ++j) {
            Luminaire l = standard_luminaire(view);
            l.position = {(i + 0.5) * kSpacing, kHeight, -half_width + (j + 0.5) * kSpacing};
            set.luminaires.push_back(l);
        }
    *luminaires = static_cast<long>(set.luminaires.size());
    const ObserverGlare glare = observer_glare(set, nullptr, {0, 0, 0}, {1, 0, 0}, 1.0);
    double sum = 0;
    for (const auto& term : glare.terms) sum += term.contribution();
    return sum;
}

// As the report writes numbers, with "-" where no luminaire counts.
std::string fixed(double value, int decimals) {
    return std::isnan(value) ? "-" : report_text::fixed(value, decimals);
}

// A UGR as data sheets print it: CIE 117's scale runs from 10 (glare imperceptible) up, so a
// value below it (an uplight's, say, which can be negative) is "<10", as Relux prints it.
std::string shown(double ugr) {
    return ugr < 10 ? "<10" : fixed(ugr, 1);
}

} // namespace

WallTransfer wall_transfer(double across, double along, const RoomReflectances& rho) {
    const double floor_area = across * along, wall_area = 2 * (across + along);
    const double floor_ceiling = parallel_rectangles_form_factor(across, along, 1);
    const double floor_walls = 1 - floor_ceiling;
    const double walls_floor = floor_walls * floor_area / wall_area; // reciprocity
    const double walls_walls = 1 - 2 * walls_floor;
    // Form factors F[i][j] from surface i to j (0 floor, 1 walls, 2 ceiling).
    const std::array<std::array<double, 3>, 3> form{{{0, floor_walls, floor_ceiling},
                                                     {walls_floor, walls_walls, walls_floor},
                                                     {floor_ceiling, floor_walls, 0}}};
    const std::array<double, 3> reflectance{rho.floor, rho.walls, rho.ceiling};
    // The flux arriving at each surface: its first flux plus what the others reflect to it,
    // phi_i = phi0_i + sum_j rho_j phi_j F[j][i].
    std::array<std::array<double, 3>, 3> system{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            system[i][j] = (i == j ? 1.0 : 0.0) - reflectance[j] * form[j][i];
    auto to_walls = [&](int first) {
        std::array<double, 3> start{};
        start[first] = 1;
        return solve3(system, start)[1] - start[1];
    };
    return {to_walls(0), to_walls(1), to_walls(2)};
}

FirstFlux standard_room_first_flux(const Photometry& photometry, const UgrRoom& room,
                                   UgrView view) {
    double upward = 0;
    const auto rays = downward_rays(photometry, view, &upward);
    return first_flux(rays, upward, room);
}

UgrTable ugr_table(const Photometry& photometry) {
    if (!(photometry.length > 0))
        throw InputError(photometry.source +
                         ": gives no luminous opening (its luminous area's length is 0), so its "
                         "luminance and its UGR are undefined; a UGR table needs the file's "
                         "luminous dimensions");
    UgrTable table;
    table.luminaire = photometry.source;
    table.lamp_flux = lamp_flux_of(photometry);
    if (!(table.lamp_flux > 0))
        throw InputError(photometry.source + ": gives no light (its intensities are all 0), so it "
                                             "has no UGR table");
    for (int v = 0; v < 2; ++v) {
        const UgrView view = v == 0 ? UgrView::crosswise : UgrView::endwise;
        double upward = 0;
        const auto rays = downward_rays(photometry, view, &upward);
        for (std::size_t r = 0; r < kUgrTableRooms.size(); ++r) {
            const UgrRoom& room = kUgrTableRooms[r];
            const FirstFlux first = first_flux(rays, upward, room);
            if (v == 0 && r == 0) {
                table.downward = first.floor + first.walls;
                table.upward = first.ceiling;
            }
            long count = 0;
            const double sum = glare_sum(photometry, room, view, &count);
            const double wall_area = 2 * kHeight * (room.across + room.along) * kHeight;
            for (std::size_t k = 0; k < kUgrTableReflectances.size(); ++k) {
                const WallTransfer t =
                    wall_transfer(room.across, room.along, kUgrTableReflectances[k]);
                const double wall_indirect =
                    table.lamp_flux * count / wall_area *
                    (first.floor * t.from_floor + first.walls * t.from_walls +
                     first.ceiling * t.from_ceiling);
                const double background = wall_indirect / std::numbers::pi;
                table.background[r][v * 5 + k] = background;
                table.ugr[r][v * 5 + k] = sum > 0 && background > 0
                                              ? 8 * std::log10(0.25 / background * sum)
                                              : std::nan("");
            }
        }
    }
    return table;
}

std::string ugr_table_text(const UgrTable& t) {
    std::string out =
        "UGR table, CIE 190:2010's tabular method (CIE 117's formula): " + t.luminaire + "\n";
    out += "For " + fixed(t.lamp_flux, 0) + " lm of lamp flux (another flux F: add 8 log10(F / " +
           fixed(t.lamp_flux, 0) + ")); DLOR " + fixed(t.downward, 3) + ", ULOR " +
           fixed(t.upward, 3) +
           "; luminaires every 0.25H, H = 2 m above the eye; below 10 "
           "(CIE 117's scale): <10\n\n";
    auto reflectance_row = [&](const char* name, double RoomReflectances::*field) {
        std::string row = name;
        row.resize(18, ' ');
        for (int v = 0; v < 2; ++v) {
            for (const auto& r : kUgrTableReflectances) row += "  " + fixed(r.*field, 2);
            row += v == 0 ? "   " : "";
        }
        return row + "\n";
    };
    out += "                        viewed crosswise                 viewed endwise\n";
    out += reflectance_row("ceiling", &RoomReflectances::ceiling);
    out += reflectance_row("walls", &RoomReflectances::walls);
    out += reflectance_row("reference plane", &RoomReflectances::floor);
    out += "room X    Y\n";
    for (std::size_t r = 0; r < kUgrTableRooms.size(); ++r) {
        const auto& room = kUgrTableRooms[r];
        const bool first_of_width = r == 0 || kUgrTableRooms[r - 1].across != room.across;
        std::string row = first_of_width ? "     " + std::to_string(room.across) + "H" : "";
        row.resize(10, ' ');
        row += std::to_string(room.along) + "H";
        row.resize(18, ' ');
        for (int c = 0; c < 10; ++c) {
            std::string cell = shown(t.ugr[r][c]);
            row += std::string(6 - std::min<std::size_t>(6, cell.size()), ' ') + cell;
            if (c == 4) row += "   ";
        }
        out += row + "\n";
    }
    return out;
}

std::string ugr_table_csv(const UgrTable& t) {
    std::string out = "x_h,y_h,view,ceiling,walls,floor,ugr,lb\n";
    for (std::size_t r = 0; r < kUgrTableRooms.size(); ++r)
        for (int c = 0; c < 10; ++c) {
            const auto& room = kUgrTableRooms[r];
            const auto& rho = kUgrTableReflectances[c % 5];
            out += std::to_string(room.across) + "," + std::to_string(room.along) + "," +
                   (c < 5 ? "crosswise" : "endwise") + "," + fixed(rho.ceiling, 2) + "," +
                   fixed(rho.walls, 2) + "," + fixed(rho.floor, 2) + "," + fixed(t.ugr[r][c], 2) +
                   "," + fixed(t.background[r][c], 3) + "\n";
        }
    return out;
}

std::string ugr_table_html(const UgrTable& t, const std::string& title) {
    std::string out =
        "<table class=\"ugr-table\"><caption>" + html_escape(title) + ": UGR for " +
        fixed(t.lamp_flux, 0) +
        " lm of lamp flux (CIE 190:2010's tabular method, S = 0.25H; below 10, CIE 117's scale: "
        "&lt;10)</caption>";
    out += "<thead><tr><th colspan=\"2\">Reflectances</th><th colspan=\"5\">Viewed crosswise"
           "</th><th colspan=\"5\">Viewed endwise</th></tr>";
    auto reflectance_row = [&](const char* name, double RoomReflectances::*field) {
        std::string row = "<tr><th colspan=\"2\">" + std::string(name) + "</th>";
        for (int v = 0; v < 2; ++v)
            for (const auto& r : kUgrTableReflectances)
                row += "<th class=\"num\">" + fixed(r.*field, 2) + "</th>";
        return row + "</tr>";
    };
    out += reflectance_row("ceiling", &RoomReflectances::ceiling);
    out += reflectance_row("walls", &RoomReflectances::walls);
    out += reflectance_row("reference plane", &RoomReflectances::floor);
    out += "<tr><th>X</th><th>Y</th><th colspan=\"10\">UGR</th></tr></thead><tbody>";
    for (std::size_t r = 0; r < kUgrTableRooms.size(); ++r) {
        const auto& room = kUgrTableRooms[r];
        out += "<tr><th>" + std::to_string(room.across) + "H</th><th>" +
               std::to_string(room.along) + "H</th>";
        for (int c = 0; c < 10; ++c) out += "<td class=\"num\">" + shown(t.ugr[r][c]) + "</td>";
        out += "</tr>";
    }
    return out + "</tbody></table>";
}

} // namespace rad
