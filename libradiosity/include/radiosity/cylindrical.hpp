// Cylindrical illuminance (EN 12464-1:2021's Ez): the mean illuminance on the curved side of a
// small vertical cylinder at a point, Ez = (1/pi) x the integral of L sin(theta) over the
// sphere (theta from the cylinder's axis); with the horizontal illuminance Eh at the same
// point, the modelling index Ez/Eh.
#pragma once
#include "radiosity/gather.hpp"
#include "radiosity/luminaires.hpp"

#include <limits>
#include <string>

namespace rad {

struct CylindricalIlluminance {
    double cylindrical = 0, error = 0; // Ez and its standard error, lux
    // With a facing: the semi-cylindrical illuminance E_sc toward it (the mean over the curved
    // half of a small vertical half-cylinder facing that way) and its standard error; else NaN.
    double semi_cylindrical = std::numeric_limits<double>::quiet_NaN();
    double semi_error = std::numeric_limits<double>::quiet_NaN();
    double horizontal = 0;  // Eh facing up the axis, lux
    bool at_budget = false; // some direction stopped at the ray budget
};

// Ez at `point` about the axis `up` (unit): the luminaires' light exactly (a far luminaire
// gives I sin(theta) / (pi d^2), its illuminance on the vertical plane facing it over pi; a
// near one, the mean of its vertical illuminance over kCylinderAzimuths directions), the
// solution's light as the mean of the vertical illuminance gathered in kCylinderAzimuths
// directions (the mean over all azimuths of the vertical illuminance is Ez exactly; eight
// cancel every harmonic of the light below the eighth). Each direction has its own stream,
// from `index`. `problem` says why there is no value (inside an object, too far to trace).
// The luminaires' images in mirrors are not counted. With `facing` (a unit horizontal
// direction), E_sc = (1/pi) x the integral of L sin(theta) (1 + cos(psi)) too (psi: the
// horizontal angle from the facing): a far luminaire's is its Ez x (1 + cos psi), the room's
// from the same eight vertical gathers (exact for the light's first harmonic in azimuth).
inline constexpr int kCylinderAzimuths = 8;
CylindricalIlluminance cylindrical_illuminance(const Gatherer& gatherer,
                                               const LuminaireSet* luminaires, const Box& box,
                                               const Vec3& point, const Vec3& up,
                                               std::uint64_t index, std::string& problem,
                                               const Vec3* facing = nullptr);

} // namespace rad
