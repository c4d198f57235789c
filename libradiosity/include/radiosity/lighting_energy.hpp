// The lighting energy numeric indicator (LENI) of EN 15193-1, by the standard's quick method:
// a room's installed power over a year of operating hours by building type, scaled by the
// dependency factors of its controls, plus the parasitic energy of the controls' standby and
// the emergency luminaires' charging, over the floor area.
//
//   W_L = P_n F_C (t_D F_O F_D + t_N F_O) / 1000              kWh a year
//   W_P = (P_pc (t_y - (t_D + t_N)) + P_em t_e) / 1000         kWh a year
//   LENI = (W_L + W_P) / A                                    kWh/(m^2 a)
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace rad {

struct LightingEnergyInputs {
    std::string building;            // the building type the operating hours are for
    double daylight_hours = 0;       // t_D: hours a year the lighting runs with daylight present
    double night_hours = 0;          // t_N: hours a year it runs without
    double constant_illuminance = 1; // F_C: 1 without constant-illuminance control, 0.9 with
    double occupancy = 1;            // F_O: 1 for manual switching
    double daylight = 1;             // F_D: 1 without daylight-dependent control
    double controls_watts = 0;       // P_pc: the controls' standby power while the lamps are off
    double emergency_watts = 0;      // P_em: the emergency luminaires' charging power
    double charge_hours = 8760;      // t_e: the hours a year they charge
    std::vector<std::string> given;  // the keys the user set (the others are the defaults)
};

struct LightingEnergy {
    LightingEnergyInputs inputs;
    double lighting_watts = 0, area_m2 = 0; // P_n, A
    double lighting_kwh = 0, parasitic_kwh = 0;
    double total_kwh() const { return lighting_kwh + parasitic_kwh; }
    double leni() const { return total_kwh() / area_m2; }
};

constexpr double kHoursInYear = 8760; // t_y

// The building types EN 15193-1's quick method tabulates operating hours for, in its order.
std::vector<std::string> lighting_energy_buildings();

// "office" or "office,FO=0.9,FD=0.8,Ppc=4.5,Pem=2": a building type (its t_D and t_N) and
// any of tD, tN, FC, FO, FD, Ppc, Pem, te. Throws InputError naming what is wrong.
LightingEnergyInputs parse_lighting_energy(std::string_view spec);

// The year's energy of `lighting_watts` (P_n, the luminaires' input power) over `area_m2`.
// Throws InputError when either is not positive.
LightingEnergy lighting_energy(const LightingEnergyInputs& inputs, double lighting_watts,
                               double area_m2);

} // namespace rad
