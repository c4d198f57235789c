// Spectral power distributions of light sources, sampled every 5 nm from 380 to 780 nm, and
// the CIE functions they are weighed with: the photopic V(lambda) (CIE 1924, the CIE 1931
// observer's y-bar) and the melanopic action spectrum of CIE S 026:2018.
#pragma once
#include <array>
#include <string>

namespace rad {

struct Spectrum {
    static constexpr int kFirstNm = 380, kStepNm = 5, kCount = 81; // 380, 385, ..., 780 nm
    std::array<double, kCount> values{}; // relative spectral power (any scale)
    std::string name;                    // as messages and summaries say it
    static constexpr double wavelength(int k) { return kFirstNm + kStepNm * k; }
};

// CIE standard illuminant D65 (CIE 015:2018, Table 5, 5 nm).
Spectrum cie_d65();
// CIE standard illuminant A as the CIE defines it (CIE 015:2018, eq. 2.1): a Planckian
// radiator at 2848 K with c2 = 1.435e-2 m K (2856 K with today's c2 = 1.4388e-2).
Spectrum cie_illuminant_a();
// A Planckian radiator at `kelvin` (c2 = 1.4388e-2 m K), within [1000, 25000] K: a lamp
// known only by its colour temperature.
Spectrum blackbody(double kelvin);
// A spectrum from a CSV file of "wavelength_nm,value" rows (a header row, # comments and
// blank lines allowed; tab or ';' also separate), wavelengths increasing, values >= 0;
// linearly interpolated onto the 5 nm grid, 0 outside the file's range. InputError at
// FILE:LINE for anything else, and for a spectrum with no light between 380 and 780 nm.
Spectrum read_spectrum_csv(const std::string& path);
// "d65", "a", "cct:K" (a blackbody) or the path of a spectrum CSV; InputError otherwise.
Spectrum parse_spectrum(const std::string& text);

// The CIE weighting functions on the same grid.
const std::array<double, Spectrum::kCount>& photopic_efficiency(); // V(lambda), peak 1
const std::array<double, Spectrum::kCount>& melanopic_action();    // s_mel(lambda), peak 1

} // namespace rad
