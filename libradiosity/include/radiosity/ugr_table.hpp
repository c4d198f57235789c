// CIE 190:2010's tabular UGR: a luminaire type's Unified Glare Rating in CIE's standard rooms
// from its photometry alone, as data sheets print it. The standard room: the luminaires' plane
// H = 2 m above the eye, a grid of them at spacing 0.25 H filling the ceiling, the observer at
// the middle of one wall looking horizontally along the room; X (across the line of sight)
// from 2H to 12H and Y (along it) from 2H to 12H; the ceiling, walls and reference plane (at
// the eye) of five reflectance combinations. The sum over the grid is CIE 117's
// (observer_glare); the background luminance is CIE 190's: Lb = E_WID / pi, the indirect
// illuminance of the walls, from the luminaire's first flux on the reference plane, walls and
// ceiling and the room's inter-reflections.
#pragma once
#include "radiosity/photometry.hpp"

#include <array>
#include <string>

namespace rad {

// A standard room in units of H: `across` the line of sight (X) and `along` it (Y).
struct UgrRoom {
    int across = 0, along = 0;
};
// CIE 190's 19 rooms, in the order data sheets print them.
inline constexpr std::array<UgrRoom, 19> kUgrTableRooms{{{2, 2},
                                                         {2, 3},
                                                         {2, 4},
                                                         {2, 6},
                                                         {2, 8},
                                                         {2, 12},
                                                         {4, 2},
                                                         {4, 3},
                                                         {4, 4},
                                                         {4, 6},
                                                         {4, 8},
                                                         {4, 12},
                                                         {8, 4},
                                                         {8, 6},
                                                         {8, 8},
                                                         {8, 12},
                                                         {12, 4},
                                                         {12, 6},
                                                         {12, 8}}};

struct RoomReflectances {
    double ceiling = 0, walls = 0, floor = 0; // floor: the reference plane at the eye
};
// The five combinations data sheets print (ceiling / walls / reference plane).
inline constexpr std::array<RoomReflectances, 5> kUgrTableReflectances{
    {{0.7, 0.5, 0.2}, {0.7, 0.3, 0.2}, {0.5, 0.5, 0.2}, {0.5, 0.3, 0.2}, {0.3, 0.3, 0.2}}};

// How the observer sees the luminaires: crosswise, the line of sight in their C0-C180 plane
// (across a linear luminaire whose C0 plane is its cross-section, as EULUMDAT files measure
// them); endwise, in their C90-C270 plane.
enum class UgrView { crosswise, endwise };

// CIE 190's transfer factors of a room (sizes in units of its height, between the reference
// plane and the luminaires' plane) to its walls' indirect illuminance: the flux that reaches
// the walls after at least one reflection, per unit of flux first landing on the reference
// plane (F_T,FW), on the walls (F_T,WW - 1) and on the ceiling (F_T,CW); the three surfaces
// each uniform, exchanging light by their exact form factors.
struct WallTransfer {
    double from_floor = 0, from_walls = 0, from_ceiling = 0;
};
WallTransfer wall_transfer(double across, double along, const RoomReflectances& reflectances);

// Where the luminaires' light first lands in the standard room, as shares of their lamps'
// flux: the reference plane (F_DF), the walls (F_DW, the rest of the downward light) and the
// ceiling (F_DC, the upward light). F_DF is the downward intensity integrated over the
// directions that reach the reference plane, each weighted by the share of the grid's
// positions from which it lands inside the room (the 0.25 H grid as a uniform spread).
struct FirstFlux {
    double floor = 0, walls = 0, ceiling = 0;
};
FirstFlux standard_room_first_flux(const Photometry& photometry, const UgrRoom& room, UgrView view);

struct UgrTable {
    std::string luminaire; // the file's name
    double lamp_flux = 0;  // lm the values are for (the file's lamps; absolute files: flux)
    double downward = 0;   // DLOR, share of the lamp flux
    double upward = 0;     // ULOR
    // ugr[room][view * 5 + reflectance], rooms and reflectances as kUgrTableRooms and
    // kUgrTableReflectances; NaN where no luminaire counts. background: CIE 190's Lb (cd/m^2)
    // at the same places.
    std::array<std::array<double, 10>, kUgrTableRooms.size()> ugr{}, background{};
};

// The table for the luminaire `photometry` describes, at its lamps' flux. InputError when the
// file gives no luminous opening (its luminance is undefined), naming the file.
UgrTable ugr_table(const Photometry& photometry);

// The table as data sheets lay it out (fixed-width text), and as CSV rows
// (x_h,y_h,view,ceiling,walls,floor,ugr,lb: the background luminance, cd/m^2).
std::string ugr_table_text(const UgrTable& table);
std::string ugr_table_csv(const UgrTable& table);
// The table as an HTML <table> (class "ugr-table") for the report, with its caption.
std::string ugr_table_html(const UgrTable& table, const std::string& title);

} // namespace rad
