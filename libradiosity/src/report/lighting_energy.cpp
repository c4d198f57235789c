// EN 15193-1's LENI by its quick method: the building type's operating hours, the controls'
// dependency factors and the parasitic powers, read from a short spec, then the formula.
#include "radiosity/lighting_energy.hpp"

#include "radiosity/error.hpp"

#include <array>
#include <charconv>
#include <cmath>

namespace rad {
namespace {

struct BuildingHours {
    const char* name;
    double daylight, night; // t_D, t_N
};

// The quick method's default annual operating hours (EN 15193:2007, Annex F).
constexpr std::array<BuildingHours, 8> kBuildings{{{"office", 2250, 250},
                                                   {"education", 1800, 200},
                                                   {"hospital", 3000, 2000},
                                                   {"hotel", 3000, 2000},
                                                   {"restaurant", 1250, 1250},
                                                   {"sports", 2000, 2000},
                                                   {"retail", 3000, 2000},
                                                   {"manufacturing", 2500, 1500}}};

std::string buildings_text() {
    std::string text;
    for (const auto& b : kBuildings) text += (text.empty() ? "" : ", ") + std::string(b.name);
    return text;
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

double number_of(std::string_view key, std::string_view text) {
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
        value < 0)
        throw InputError("--energy: " + std::string(key) + "=" + std::string(text) +
                         " is not a number of 0 or more");
    return value;
}

// Sets the field `key` names; false when no field has that name.
bool set_field(LightingEnergyInputs& in, std::string_view key, double value) {
    const std::array<std::pair<const char*, double*>, 8> fields{{
        {"tD", &in.daylight_hours},
        {"tN", &in.night_hours},
        {"FC", &in.constant_illuminance},
        {"FO", &in.occupancy},
        {"FD", &in.daylight},
        {"Ppc", &in.controls_watts},
        {"Pem", &in.emergency_watts},
        {"te", &in.charge_hours},
    }};
    for (const auto& [name, field] : fields)
        if (key == name) {
            *field = value;
            return true;
        }
    return false;
}

void check_ranges(const LightingEnergyInputs& in) {
    for (const auto& [name, factor] : {std::pair{"FC", in.constant_illuminance},
                                       std::pair{"FO", in.occupancy}, std::pair{"FD", in.daylight}})
        if (factor > 1)
            throw InputError(std::string("--energy: ") + name + " is a dependency factor, 0 to 1");
    if (in.daylight_hours + in.night_hours > kHoursInYear)
        throw InputError("--energy: tD + tN is more than the year's 8760 hours");
    if (in.charge_hours > kHoursInYear)
        throw InputError("--energy: te is more than the year's 8760 hours");
}

} // namespace

std::vector<std::string> lighting_energy_buildings() {
    std::vector<std::string> names;
    for (const auto& b : kBuildings) names.emplace_back(b.name);
    return names;
}

LightingEnergyInputs parse_lighting_energy(std::string_view spec) {
    LightingEnergyInputs in;
    bool first = true;
    while (true) {
        const auto comma = spec.find(',');
        const auto item = trimmed(spec.substr(0, comma));
        if (first) {
            for (const auto& b : kBuildings)
                if (item == b.name) {
                    in.building = b.name;
                    in.daylight_hours = b.daylight;
                    in.night_hours = b.night;
                }
            if (in.building.empty())
                throw InputError("--energy: '" + std::string(item) +
                                 "' is not a building type; give one of " + buildings_text() +
                                 " first, then any of tD, tN, FC, FO, FD, Ppc, Pem, te as "
                                 "KEY=VALUE (e.g. office,FO=0.9)");
            first = false;
        } else {
            const auto equals = item.find('=');
            const auto key = trimmed(item.substr(0, equals));
            if (equals == std::string_view::npos ||
                !set_field(in, key, number_of(key, trimmed(item.substr(equals + 1)))))
                throw InputError("--energy: '" + std::string(item) +
                                 "' is not KEY=VALUE with a key of tD, tN, FC, FO, FD, Ppc, "
                                 "Pem, te (they are case-sensitive)");
            in.given.emplace_back(key);
        }
        if (comma == std::string_view::npos) break;
        spec.remove_prefix(comma + 1);
    }
    check_ranges(in);
    return in;
}

LightingEnergy lighting_energy(const LightingEnergyInputs& inputs, double lighting_watts,
                               double area_m2) {
    if (!(lighting_watts > 0))
        throw InputError("--energy: the luminaires' input power is unknown (no photometric "
                         "file gives input watts); LENI needs it");
    if (!(area_m2 > 0))
        throw InputError("--energy: no floor area to spread the energy over; give --area");
    LightingEnergy e;
    e.inputs = inputs;
    e.lighting_watts = lighting_watts;
    e.area_m2 = area_m2;
    const auto& in = inputs;
    e.lighting_kwh =
        lighting_watts * in.constant_illuminance *
        (in.daylight_hours * in.occupancy * in.daylight + in.night_hours * in.occupancy) / 1000;
    e.parasitic_kwh = (in.controls_watts * (kHoursInYear - (in.daylight_hours + in.night_hours)) +
                       in.emergency_watts * in.charge_hours) /
                      1000;
    return e;
}

} // namespace rad
