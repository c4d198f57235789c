#include "radiosity/spectrum.hpp"

#include "radiosity/error.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/text_input.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace rad {
namespace {

using Table = std::array<double, Spectrum::kCount>;

std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// CIE 1924 photopic luminous efficiency V(lambda), 380-780 nm every 5 nm (CIE 015:2018).
constexpr Table kPhotopic = {
    3.9e-05,   6.4e-05,   0.00012,  0.000217, 0.000396, 0.00064,  0.00121, 0.00218,  0.004,
    0.0073,    0.0116,    0.01684,  0.023,    0.0298,   0.038,    0.048,   0.06,     0.0739,
    0.09098,   0.1126,    0.13902,  0.1693,   0.20802,  0.2586,   0.323,   0.4073,   0.503,
    0.6082,    0.71,      0.7932,   0.862,    0.91485,  0.954,    0.9803,  0.99495,  1,
    0.995,     0.9786,    0.952,    0.9154,   0.87,     0.8163,   0.757,   0.6949,   0.631,
    0.5668,    0.503,     0.4412,   0.381,    0.321,    0.265,    0.217,   0.175,    0.1382,
    0.107,     0.0816,    0.061,    0.04458,  0.032,    0.0232,   0.017,   0.01192,  0.00821,
    0.005723,  0.004102,  0.002929, 0.002091, 0.001484, 0.001047, 0.00074, 0.00052,  0.0003611,
    0.0002492, 0.0001719, 0.00012,  8.48e-05, 6e-05,    4.24e-05, 3e-05,   2.12e-05, 1.499e-05,
};

// CIE S 026:2018 melanopic action spectrum s_mel(lambda), 380-780 nm every 5 nm (the CIE's
// S 026 toolbox, v1.049).
constexpr Table kMelanopic = {
    0.000918165, 0.00166724,  0.00309442,  0.00588035,  0.0114277,   0.0228112,   0.046155,
    0.0794766,   0.137237,    0.187096,    0.253865,    0.320679,    0.401587,    0.474002,
    0.553715,    0.629654,    0.708049,    0.785216,    0.860291,    0.917734,    0.965605,
    0.990621,    1,           0.992022,    0.965952,    0.922299,    0.862888,    0.785233,
    0.699628,    0.609422,    0.519309,    0.432533,    0.351707,    0.279135,    0.215722,
    0.162056,    0.118526,    0.0843457,   0.0587013,   0.0400089,   0.0268747,   0.0178624,
    0.0117901,   0.0077343,   0.00506686,  0.00331766,  0.00217698,  0.00143314,  0.000947313,
    0.000627648, 0.000417955, 0.000279801, 0.000188341, 0.000127337, 8.65751e-05, 5.91914e-05,
    4.06945e-05, 2.8132e-05,  1.95535e-05, 1.3648e-05,  9.57637e-06, 6.75425e-06, 4.78804e-06,
    3.40841e-06, 2.43819e-06, 1.75252e-06, 1.2656e-06,  9.18078e-07, 6.68991e-07, 4.89531e-07,
    3.59766e-07, 2.65493e-07, 1.9674e-07,  1.4637e-07,  1.09332e-07, 8.19587e-08, 6.16749e-08,
    4.65916e-08, 3.53272e-08, 2.68803e-08, 2.05258e-08,
};

// CIE standard illuminant D65, 380-780 nm every 5 nm (CIE 015:2018).
constexpr Table kD65 = {
    49.9755, 52.3118, 54.6482, 68.7015, 82.7549, 87.1204, 91.486,  92.4589, 93.4318,
    90.057,  86.6823, 95.7736, 104.865, 110.936, 117.008, 117.41,  117.812, 116.336,
    114.861, 115.392, 115.923, 112.367, 108.811, 109.082, 109.354, 108.578, 107.802,
    106.296, 104.79,  106.239, 107.689, 106.047, 104.405, 104.225, 104.046, 102.023,
    100,     98.1671, 96.3342, 96.0611, 95.788,  92.2368, 88.6856, 89.3459, 90.0062,
    89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886, 83.4939, 83.6992, 81.863,
    80.0268, 80.1207, 80.2146, 81.2462, 82.2778, 80.281,  78.2842, 74.0027, 69.7213,
    70.6652, 71.6091, 72.979,  74.349,  67.9765, 61.604,  65.7448, 69.8856, 72.4863,
    75.087,  69.3398, 63.5927, 55.0054, 46.4182, 56.6118, 66.8054, 65.0941, 63.3828,
};

Spectrum planckian(double kelvin, double c2, std::string name) {
    Spectrum s;
    s.name = std::move(name);
    for (int k = 0; k < Spectrum::kCount; ++k) {
        const double metres = Spectrum::wavelength(k) * 1e-9;
        // Relative spectral radiance; the constant c1 cancels in every ratio taken of it.
        s.values[std::size_t(k)] = 1 / (std::pow(metres, 5) * std::expm1(c2 / (metres * kelvin)));
    }
    return s;
}

// "380,0.1" / "380;0.1" / "380\t0.1" -> two numbers; false when the line is not that.
bool split_row(const std::string& line, double& nm, double& value) {
    const auto at = line.find_first_of(",;\t");
    if (at == std::string::npos) return false;
    auto trim = [](std::string t) {
        const auto b = t.find_first_not_of(" \t\r"), e = t.find_last_not_of(" \t\r");
        return b == std::string::npos ? std::string() : t.substr(b, e - b + 1);
    };
    return parse_number(trim(line.substr(0, at)), nm) &&
           parse_number(trim(line.substr(at + 1)), value);
}

// The samples interpolated onto the 5 nm grid, 0 outside [first, last].
Spectrum resample(const std::vector<std::pair<double, double>>& rows, const std::string& name) {
    Spectrum s;
    s.name = name;
    std::size_t j = 0;
    for (int k = 0; k < Spectrum::kCount; ++k) {
        const double nm = Spectrum::wavelength(k);
        if (nm < rows.front().first || nm > rows.back().first) continue;
        while (j + 1 < rows.size() && rows[j + 1].first < nm) ++j;
        if (j + 1 == rows.size()) {
            s.values[std::size_t(k)] = rows[j].second;
            continue;
        }
        const auto& [x0, y0] = rows[j];
        const auto& [x1, y1] = rows[j + 1];
        s.values[std::size_t(k)] = x1 > x0 ? y0 + (y1 - y0) * (nm - x0) / (x1 - x0) : y1;
    }
    return s;
}

} // namespace

const Table& photopic_efficiency() {
    return kPhotopic;
}
const Table& melanopic_action() {
    return kMelanopic;
}

Spectrum cie_d65() {
    Spectrum s;
    s.name = "CIE D65";
    s.values = kD65;
    return s;
}

Spectrum cie_illuminant_a() {
    return planckian(2848, 1.435e-2, "CIE illuminant A");
}

Spectrum blackbody(double kelvin) {
    if (!(kelvin >= 1000 && kelvin <= 25000))
        throw InputError("a blackbody's colour temperature must be within 1000 to 25000 K, not " +
                         number_text(kelvin));
    return planckian(kelvin, 1.4388e-2, number_text(kelvin) + " K blackbody");
}

Spectrum read_spectrum_csv(const std::string& path) {
    LineReader in(path);
    std::vector<std::pair<double, double>> rows;
    std::string line;
    while (in.next(line)) {
        const FileLoc where{path, in.line_number()};
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        double nm = 0, value = 0;
        if (!split_row(line, nm, value)) {
            if (rows.empty() && in.line_number() == 1) continue; // a header row
            throw InputError(where, "expected 'wavelength_nm,value' (two numbers), not '" +
                                        line.substr(0, 60) + "'");
        }
        if (!(nm >= 100 && nm <= 2000))
            throw InputError(where, "wavelength " + number_text(nm) +
                                        " nm is not light (give nanometres, 100 to 2000)");
        if (!(value >= 0) || !std::isfinite(value))
            throw InputError(where, "spectral power " + number_text(value) +
                                        " must be a finite number >= 0");
        if (!rows.empty() && !(nm > rows.back().first))
            throw InputError(where, "wavelength " + number_text(nm) +
                                        " nm does not increase (the row before has " +
                                        number_text(rows.back().first) + " nm)");
        rows.emplace_back(nm, value);
    }
    if (rows.size() < 2)
        throw InputError(path + ": a spectrum needs at least two 'wavelength_nm,value' rows");
    auto s = resample(rows, path);
    double light = 0;
    for (int k = 0; k < Spectrum::kCount; ++k)
        light += s.values[std::size_t(k)] * kPhotopic[std::size_t(k)];
    if (!(light > 0))
        throw InputError(path + ": the spectrum has no visible light between 380 and 780 nm "
                                "(photopically weighted it is 0)");
    return s;
}

Spectrum parse_spectrum(const std::string& text) {
    if (text == "d65" || text == "D65") return cie_d65();
    if (text == "a" || text == "A") return cie_illuminant_a();
    if (text.rfind("cct:", 0) == 0) {
        double kelvin = 0;
        if (!parse_number(text.substr(4), kelvin))
            throw InputError("spectrum '" + text +
                             "': cct:K takes a colour temperature in K, "
                             "e.g. cct:3000");
        return blackbody(kelvin);
    }
    if (text.empty())
        throw InputError("an empty spectrum: give d65, a, cct:K or a CSV file of "
                         "wavelength_nm,value rows");
    return read_spectrum_csv(text);
}

} // namespace rad
