// A camera for a scene given none (rad-shade without --view). In an interior (the median of
// the points where people would stand, over its floors, is enclosed: a closed room, a game
// level, a house under its roof) the camera stands inside at 0.55 of the floor-to-ceiling
// height, looking level; otherwise it is also offered the views from outside each side of the
// scene's box. Of those, the one whose probe rays meet the most patches from their front and
// the fewest backs (an open box from its open side); a view seeing no front is the last resort.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/view.hpp"

#include <string>

namespace rad {

struct ChosenView {
    View view;
    std::string text;       // the view as -vp/-vd/-vu/-vh/-vv options
    double front_share = 0; // the share of its probe rays that meet a surface's front
    std::string where;      // "outside, from +z", "inside, towards -x+z, standing over a floor"
};

// `aspect` is the image's width over its height. Deterministic; +y is up (the OBJ and glTF
// convention) unless far more of the level surfaces face along z (a z-up export).
ChosenView choose_view(const radfmt::MeshData& mesh, const RayScene& scene, double aspect);

// A view as the options that give it: "-vp x y z -vd x y z -vu x y z -vh h -vv v".
std::string view_text(const View& view);

} // namespace rad
