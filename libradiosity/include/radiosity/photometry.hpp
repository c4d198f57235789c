// Photometric files (IES LM-63 of every edition, EULUMDAT): a luminaire's intensity
// distribution in candela, read into one web over its photometric system, interpolated as the
// formats intend (bilinear in the two angles, symmetric parts mirrored) and integrated to its
// flux. Readers take text (the chain's .lum files carry the files' text, so a later tool needs
// no other file) and refuse a malformed file with FILE:LINE and what is wrong.
#pragma once
#include "radiosity/error.hpp"

#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

// The photometric systems of LM-63 (EULUMDAT is always C). The angles are degrees.
//  C: polar axis through the nadir; h is the C-plane (azimuth, [0, 360)), v is gamma from
//     the nadir ([0, 180]).
//  B: polar axis horizontal and lateral (the C90 direction); v turns the plane about it
//     (up towards C0), h is the angle within the plane from the beam axis (towards C90).
//  A: polar axis along the luminaire's up (C0); h is the angle about it from the beam axis
//     (towards C90), v the elevation from that plane.
enum class PhotometricType { C = 1, B = 2, A = 3 };

// A TILT table: multipliers of the intensity by the angle the luminaire is tilted from the
// attitude it was measured in (LM-63's lamp-to-luminaire geometry says how the lamp lies).
struct TiltTable {
    int geometry = 0; // 1: lamp vertical; 2, 3: horizontal along C0-C180 / C90-C270
    std::vector<double> angles, factors;
    bool empty() const { return angles.empty(); }
    // The multiplier at `degrees` (linear between entries, the end values beyond them).
    double factor(double degrees) const;
};

struct Photometry {
    std::string source;  // the file's name, for messages
    std::string edition; // "LM-63-2002", "LM-63-1995", ..., "EULUMDAT"
    PhotometricType type = PhotometricType::C;
    // The full web: h ascending over the whole range (type C: 0 to 360, both ends present;
    // A, B: -90 to 90 where the file had half), v ascending as the file gives it (outside
    // [v.front(), v.back()] the intensity is 0). candela[ih * v.size() + iv], in candela
    // with every multiplier of the file applied.
    std::vector<double> h, v, candela;
    // What the file says about its light: lamp lumens (all lamps) for relative photometry
    // (0 for absolute), and the luminaire's flux it implies where the file gives it (EULUMDAT:
    // lamps x LORL; 0: not stated). The downward share in % (EULUMDAT's DFF; < 0: not stated).
    double lamp_lumens = 0, stated_flux = 0, stated_downward_percent = -1;
    double input_watts = 0;
    double cct = 0; // colour temperature in K (EULUMDAT's lamp set), 0 unknown
    // The colour rendering the file states (EULUMDAT's lamp set's group or CRI, an IES file's
    // [_CRI] or [CRI] keyword), as written; empty: not stated.
    std::string colour_rendering;
    // The luminous opening in metres: length along C0-C180, width along C90-C270, height;
    // `round`: a disc (or cylinder) of diameter `length`.
    double length = 0, width = 0, height = 0;
    bool round = false;
    TiltTable tilt;
    std::vector<std::pair<std::string, std::string>> keywords; // IES [KEYWORD] value

    // Intensity in candela at (h, v) degrees of the file's system; 0 outside the web.
    double intensity(double h_deg, double v_deg) const;
    // The luminous flux, lm: the intensity integrated over the sphere (each cell's bilinear
    // patch by a 4 x 4 Gauss rule with the system's Jacobian). `downward`: only gamma < 90
    // (type C; for A and B the half below the beam axis's horizontal plane is not defined:
    // the whole flux).
    double flux() const;
    double downward_flux() const;
    double peak() const;
};

// Reads a further file a photometric file names (an IES TILT=<file>): `name` as written in
// the file, `where` the line naming it; returns its text or throws InputError.
using IncludeReader = std::function<std::string(const std::string& name, const FileLoc& where)>;

// IES LM-63-1986/1991/1995/2002/2019. Throws InputError "NAME:LINE: what is wrong".
Photometry parse_ies(std::string_view text, const std::string& name,
                     const IncludeReader& read_include);
// EULUMDAT (.ldt), intensities in cd/klm scaled by the first lamp set's flux and the
// conversion factor. Throws InputError "NAME:LINE: what is wrong".
Photometry parse_ldt(std::string_view text, const std::string& name);
// By extension (.ldt: EULUMDAT; else IES, whose first line says so).
Photometry parse_photometry(std::string_view text, const std::string& name,
                            const IncludeReader& read_include);

// A photometric file read from disk (a TILT file it names: beside it, inside its folder).
// Throws InputError naming the file (and line), SystemError when it cannot be read.
Photometry read_photometry_file(const std::filesystem::path& path);

// What the file says of its flux against the integral (each line names the file): a
// mismatch over `tolerance` (relative) with what the file states (EULUMDAT's lamps x LORL and
// DFF; IES relative photometry whose integral exceeds its lamp lumens), as warning lines.
std::vector<std::string> flux_warnings(const Photometry& photometry, double tolerance = 0.02);

// A colour temperature's RGB tint in the chain's (Radiance's) primaries, with luminance
// 0.265 R + 0.670 G + 0.065 B = 1, so a tinted light keeps its lumens. Planckian locus
// (CIE 1931 observer tabulated at 10 nm); `kelvin` within [1000, 25000].
std::array<double, 3> cct_tint(double kelvin);

} // namespace rad
