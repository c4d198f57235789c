// The sky divided into patches for daylight coefficients: Tregenza's 145 and Reinhart's
// subdivisions of them (MF:m, 144 m^2 + 1 patches), and the ground below the horizon as one
// more, patch 0 (Radiance's numbering: the ground, then rows from the horizon up, each from
// north towards east, the zenith cap last).
#pragma once
#include "radiosity/sky.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace rad {

class SkyPatches {
  public:
    // "reinhart:M" (M = 1..12), "tregenza" (reinhart:1). InputError otherwise.
    static SkyPatches parse(const std::string& spec);
    explicit SkyPatches(int subdivisions = 1);

    int subdivisions() const { return m_; }
    std::string spec() const { return "reinhart:" + std::to_string(m_); }
    std::size_t count() const { return first_.back() + 2; } // ground + sky
    // The patch holding a direction of `altitude_deg`, `azimuth_deg` (ground below 0).
    std::size_t patch_of(double altitude_deg, double azimuth_deg) const;
    std::size_t patch_of(const SkyFrame& frame, const Vec3& direction) const;
    // "ground", "sky1" ... "skyN": the light groups' names.
    std::string name(std::size_t patch) const;

    struct Bounds {
        double altitude0, altitude1; // degrees
        double azimuth0, azimuth1;   // degrees, azimuth0 may be below 0 (the row's first)
    };
    Bounds bounds(std::size_t patch) const;
    double solid_angle(std::size_t patch) const;
    // The patch's directions as `side` x `side` cells of equal solid angle (their centres,
    // in sin(altitude) and azimuth), each standing for solid_angle / side^2.
    std::vector<Vec3> cell_directions(const SkyFrame& frame, std::size_t patch, int side) const;
    // A direction in cell `cell` (row-major, as cell_directions orders them) at (u, v) in
    // [0, 1)^2 across it: uniform (u, v) give directions uniform in the cell's solid angle;
    // (0.5, 0.5) is its centre.
    Vec3 cell_direction(const SkyFrame& frame, std::size_t patch, int side, int cell, double u,
                        double v) const;
    // Every patch's (the ground's first), computed once for many skies or sensors.
    using Cells = std::vector<std::vector<Vec3>>;
    Cells cells(const SkyFrame& frame, int side) const;

    // Each patch's mean luminance (cd/m^2) under `sky`, integrated over the patch (a
    // side x side grid of equal solid angle per patch, or `cells` made for the sky's frame;
    // the ground's is uniform).
    std::vector<double> mean_luminance(const Sky& sky, int side = 16) const;
    std::vector<double> mean_luminance(const Sky& sky, const Cells& cells) const;

  private:
    int m_ = 1;
    double alpha_ = 12;              // a row's height, degrees
    std::vector<std::size_t> first_; // per row, its first patch's index - 1; then the cap's
    std::vector<int> per_row_;
};

} // namespace rad
