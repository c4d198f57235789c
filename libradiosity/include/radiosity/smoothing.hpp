// Vertex smoothing: from one radiosity per patch to a colour per patch corner.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <string>
#include <vector>

namespace rad {

enum class Smoothing { Flat, Average, Area, Crease };
Smoothing parse_smoothing(const std::string& name);

// Colour at each corner of each patch. Average: the plain mean of the patches around a
// vertex (the paper's); Area: weighted by area; Crease: area-weighted over neighbours of
// the same material whose normals are within `crease_deg`, so edges stay sharp.
std::vector<std::array<Rgb, 4>> corner_colours(const radfmt::MeshData& mesh,
                                               const std::vector<Rgb>& patch, Smoothing mode,
                                               double crease_deg = 30);

} // namespace rad
