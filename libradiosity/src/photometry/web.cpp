// The photometric web: completion by symmetry, interpolation, flux integrals, TILT factors
// and colour-temperature tints.
#include "photometry/web.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace rad {
namespace photometry {

void require_increasing(const std::vector<double>& angles, const std::string& what,
                        const Fail& fail) {
    for (std::size_t i = 1; i < angles.size(); ++i)
        if (!(angles[i] > angles[i - 1]))
            fail(what + " must increase: " + std::to_string(angles[i - 1]) + " is followed by " +
                 std::to_string(angles[i]));
}

namespace {
// Builds p.h and p.candela from (angle, source plane) pairs, sorted, the first of equal
// angles kept.
void assemble(Photometry& p, std::vector<std::pair<double, std::size_t>> planes,
              const std::vector<double>& values) {
    std::stable_sort(planes.begin(), planes.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t nv = p.v.size();
    p.h.clear();
    p.candela.clear();
    for (const auto& [angle, source] : planes) {
        if (!p.h.empty() && std::abs(p.h.back() - angle) < 1e-9) continue;
        p.h.push_back(angle);
        p.candela.insert(p.candela.end(), values.begin() + long(source * nv),
                         values.begin() + long((source + 1) * nv));
    }
}

double wrap360(double a) {
    a = std::fmod(a, 360.0);
    return a < 0 ? a + 360 : a;
}
} // namespace

void complete_type_c(Photometry& p, const std::vector<double>& h, const std::vector<double>& values,
                     const Fail& fail) {
    std::vector<std::pair<double, std::size_t>> planes;
    const double first = h.front(), last = h.back();
    const auto add = [&](double angle, std::size_t source) { planes.push_back({angle, source}); };
    if (h.size() == 1) {
        add(0, 0); // rotationally symmetric
    } else if (first == 0 && last == 90) {
        for (std::size_t i = 0; i < h.size(); ++i) {
            add(h[i], i);
            add(180 - h[i], i);
            add(180 + h[i], i);
            add(wrap360(360 - h[i]), i);
        }
    } else if (first == 0 && last == 180) {
        for (std::size_t i = 0; i < h.size(); ++i) {
            add(h[i], i);
            add(wrap360(360 - h[i]), i);
        }
    } else if (first == 90 && last == 270) {
        for (std::size_t i = 0; i < h.size(); ++i) {
            add(h[i], i);
            add(wrap360(180 - h[i]), i);
        }
    } else if (first == 0 && last > 180 && last <= 360) {
        for (std::size_t i = 0; i < h.size(); ++i) add(h[i], i);
    } else {
        fail("horizontal angles from " + std::to_string(first) + " to " + std::to_string(last) +
             ": type C distributions give one plane, or planes 0-90, 0-180, 90-270 or 0-360");
    }
    // Both ends of the circle, so that every angle lies between two planes.
    const bool has0 =
        std::any_of(planes.begin(), planes.end(), [](auto& q) { return q.first == 0; });
    const bool has360 =
        std::any_of(planes.begin(), planes.end(), [](auto& q) { return q.first == 360; });
    for (const auto& q : std::vector(planes)) {
        if (q.first == 0 && !has360) add(360, q.second);
        if (q.first == 360 && !has0) add(0, q.second);
    }
    assemble(p, std::move(planes), values);
}

void complete_type_ab(Photometry& p, const std::vector<double>& h,
                      const std::vector<double>& values, const Fail& fail) {
    std::vector<std::pair<double, std::size_t>> planes;
    if (h.front() < -90 || h.back() > 90)
        fail("horizontal angles of type A and B photometry lie within -90 to 90");
    const bool half = h.front() >= 0;
    if (half && h.front() != 0)
        fail("horizontal angles of type A and B photometry start at 0 (one side, mirrored) or "
             "at -90");
    for (std::size_t i = 0; i < h.size(); ++i) {
        planes.push_back({h[i], i});
        if (half && h[i] > 0) planes.push_back({-h[i], i});
    }
    assemble(p, std::move(planes), values);
}

} // namespace photometry

double TiltTable::factor(double degrees) const {
    if (angles.empty()) return 1;
    if (degrees <= angles.front()) return factors.front();
    if (degrees >= angles.back()) return factors.back();
    const auto k =
        std::size_t(std::upper_bound(angles.begin(), angles.end(), degrees) - angles.begin());
    const double t = (degrees - angles[k - 1]) / (angles[k] - angles[k - 1]);
    return factors[k - 1] + t * (factors[k] - factors[k - 1]);
}

namespace {
// The cell [i, i + 1] of `grid` holding x, and x's fraction within it; false outside.
bool locate(const std::vector<double>& grid, double x, std::size_t& i, double& t) {
    if (grid.size() < 2 || x < grid.front() || x > grid.back()) return false;
    i = std::size_t(std::upper_bound(grid.begin(), grid.end(), x) - grid.begin());
    i = std::clamp<std::size_t>(i, 1, grid.size() - 1) - 1;
    t = (x - grid[i]) / (grid[i + 1] - grid[i]);
    return true;
}
} // namespace

double Photometry::intensity(double h_deg, double v_deg) const {
    if (type == PhotometricType::C) {
        h_deg = std::fmod(h_deg, 360.0);
        if (h_deg < 0) h_deg += 360;
    }
    std::size_t i = 0, j = 0;
    double s = 0, t = 0;
    if (!locate(h, h_deg, i, s) || !locate(v, v_deg, j, t)) return 0;
    const std::size_t nv = v.size();
    const double a = candela[i * nv + j], b = candela[i * nv + j + 1];
    const double c = candela[(i + 1) * nv + j], d = candela[(i + 1) * nv + j + 1];
    return (1 - s) * ((1 - t) * a + t * b) + s * ((1 - t) * c + t * d);
}

namespace {
// The flux over v in [v_low, v_high] (degrees): every cell's bilinear intensity times the
// solid angle's Jacobian, by a 4 x 4 Gauss-Legendre rule. The intensity is the cell's own
// bilinear (what Photometry::intensity finds by searching for the cell), and the Jacobian is
// made once per vertical (or, type B, horizontal) node: a file of 10 million values took 11 s.
double integrate(const Photometry& p, double v_low, double v_high) {
    static constexpr double kNode[4] = {-0.8611363115940526, -0.3399810435848563,
                                        0.3399810435848563, 0.8611363115940526};
    static constexpr double kWeight[4] = {0.3478548451374538, 0.6521451548625461,
                                          0.6521451548625461, 0.3478548451374538};
    constexpr double kRad = std::numbers::pi / 180;
    // A cell wider than 5 degrees is split, so the rule stays exact enough for the Jacobian
    // over wide cells (an isotropic file's one cell of 180 degrees).
    const auto pieces = [](double span) { return std::max(1, int(std::ceil(span / 5))); };
    // Per vertical cell: its clipped span and each piece's nodes' Jacobian (types C and A).
    struct Column {
        double lo = 0, hi = 0;
        int pieces = 0;
        std::vector<double> jacobian; // [piece * 4 + b]
    };
    std::vector<Column> columns(p.v.size() > 1 ? p.v.size() - 1 : 0);
    for (std::size_t j = 0; j < columns.size(); ++j) {
        auto& c = columns[j];
        c.lo = std::max(p.v[j], v_low), c.hi = std::min(p.v[j + 1], v_high);
        if (!(c.hi > c.lo)) continue;
        c.pieces = pieces(c.hi - c.lo);
        for (int pv = 0; pv < c.pieces; ++pv) {
            const double v0 = c.lo + (c.hi - c.lo) * pv / c.pieces;
            const double v1 = c.lo + (c.hi - c.lo) * (pv + 1) / c.pieces;
            const double vm = 0.5 * (v0 + v1), vr = 0.5 * (v1 - v0);
            for (int b = 0; b < 4; ++b) {
                const double vv = vm + vr * kNode[b];
                c.jacobian.push_back(p.type == PhotometricType::C ? std::sin(vv * kRad)
                                                                  : std::cos(vv * kRad));
            }
        }
    }
    const std::size_t nv_all = p.v.size();
    double total = 0;
    for (std::size_t i = 0; i + 1 < p.h.size(); ++i) {
        const double hspan = p.h[i + 1] - p.h[i];
        if (!(hspan > 0)) continue; // a plane given twice: no width, no flux
        for (std::size_t j = 0; j < columns.size(); ++j) {
            const auto& column = columns[j];
            const double lo = column.lo, hi = column.hi;
            if (!(hi > lo)) continue;
            const int nh = pieces(hspan), nv = column.pieces;
            const double a00 = p.candela[i * nv_all + j], a01 = p.candela[i * nv_all + j + 1];
            const double a10 = p.candela[(i + 1) * nv_all + j];
            const double a11 = p.candela[(i + 1) * nv_all + j + 1];
            const double vspan = p.v[j + 1] - p.v[j];
            for (int ph = 0; ph < nh; ++ph)
                for (int pv = 0; pv < nv; ++pv) {
                    const double h0 = p.h[i] + (p.h[i + 1] - p.h[i]) * ph / nh;
                    const double h1 = p.h[i] + (p.h[i + 1] - p.h[i]) * (ph + 1) / nh;
                    const double v0 = lo + (hi - lo) * pv / nv, v1 = lo + (hi - lo) * (pv + 1) / nv;
                    const double hm = 0.5 * (h0 + h1), hr = 0.5 * (h1 - h0);
                    const double vm = 0.5 * (v0 + v1), vr = 0.5 * (v1 - v0);
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) {
                            const double hh = hm + hr * kNode[a], vv = vm + vr * kNode[b];
                            const double jacobian = p.type == PhotometricType::B
                                                        ? std::cos(hh * kRad)
                                                        : column.jacobian[pv * 4 + b];
                            const double s = (hh - p.h[i]) / hspan, t = (vv - p.v[j]) / vspan;
                            const double intensity =
                                (1 - s) * ((1 - t) * a00 + t * a01) + s * ((1 - t) * a10 + t * a11);
                            total += kWeight[a] * kWeight[b] * hr * vr * kRad * kRad * jacobian *
                                     intensity;
                        }
                }
        }
    }
    return total;
}
} // namespace

double Photometry::flux() const {
    return integrate(*this, -1e9, 1e9);
}

double Photometry::downward_flux() const {
    return type == PhotometricType::C ? integrate(*this, -1e9, 90) : flux();
}

double Photometry::peak() const {
    return candela.empty() ? 0 : *std::max_element(candela.begin(), candela.end());
}

std::array<double, 3> cct_tint(double kelvin) {
    if (!(kelvin >= 1667 && kelvin <= 25000))
        throw InputError("colour temperature " + std::to_string(kelvin) +
                         " K is outside 1667 to 25000 K");
    // Kim et al. (2002): the Planckian locus in CIE 1931 xy.
    const double t = kelvin, t2 = t * t, t3 = t2 * t;
    const double x = t <= 4000 ? -0.2661239e9 / t3 - 0.2343589e6 / t2 + 0.8776956e3 / t + 0.179910
                               : -3.0258469e9 / t3 + 2.1070379e6 / t2 + 0.2226347e3 / t + 0.240390;
    const double y =
        t <= 2222   ? -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683
        : t <= 4000 ? -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867
                    : 3.0817580 * x * x * x - 5.87338670 * x * x + 3.75112997 * x - 0.37001483;
    const double X = x / y, Y = 1, Z = (1 - x - y) / y;
    // Radiance's primaries (R .640 .330, G .290 .600, B .150 .060, white E): XYZ -> RGB.
    const double prim[3][2] = {{0.640, 0.330}, {0.290, 0.600}, {0.150, 0.060}};
    double m[3][3]; // columns: each primary's XYZ at unit luminance
    for (int k = 0; k < 3; ++k) {
        m[0][k] = prim[k][0] / prim[k][1];
        m[1][k] = 1;
        m[2][k] = (1 - prim[k][0] - prim[k][1]) / prim[k][1];
    }
    // Scale the primaries so that R = G = B = 1 is the equal-energy white (X = Y = Z).
    const auto solve = [](const double a[3][3], const double b[3]) {
        const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        std::array<double, 3> out{};
        for (int k = 0; k < 3; ++k) {
            double c[3][3];
            for (int r = 0; r < 3; ++r)
                for (int q = 0; q < 3; ++q) c[r][q] = q == k ? b[r] : a[r][q];
            out[std::size_t(k)] = (c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                                   c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
                                   c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0])) /
                                  det;
        }
        return out;
    };
    const double white[3] = {1, 1, 1};
    const auto scale = solve(m, white);
    double ms[3][3];
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) ms[r][k] = m[r][k] * scale[std::size_t(k)];
    const double xyz[3] = {X, Y, Z};
    auto rgb = solve(ms, xyz);
    for (auto& c : rgb) c = std::max(0.0, c);
    const double luminance = 0.265 * rgb[0] + 0.670 * rgb[1] + 0.065 * rgb[2];
    for (auto& c : rgb) c /= luminance;
    return rgb;
}

} // namespace rad
