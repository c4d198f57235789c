// Completing a photometric web from the planes a file gives (internal header): the symmetric
// parts mirrored, so that lookups need no symmetry rules.
#pragma once
#include "radiosity/photometry.hpp"

#include <functional>
#include <string>
#include <vector>

namespace rad::photometry {

using Fail = std::function<void(const std::string&)>; // throws

// Sets p.h and p.candela from the planes `h` (ascending; values[ih * nv + iv]) in one of the
// layouts LM-63 and EULUMDAT define for type C (one plane; 0-90; 0-180; 90-270; 0 to under or
// at 360), mirrored to the full circle 0 to 360 with both ends. p.v must be set.
void complete_type_c(Photometry& p, const std::vector<double>& h, const std::vector<double>& values,
                     const Fail& fail);
// The same for types A and B: 0-90 (mirrored to -90-0) or from -90.
void complete_type_ab(Photometry& p, const std::vector<double>& h,
                      const std::vector<double>& values, const Fail& fail);
// Refuses angles that do not increase strictly, naming `what`.
void require_increasing(const std::vector<double>& angles, const std::string& what,
                        const Fail& fail);

} // namespace rad::photometry
