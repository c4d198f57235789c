// A camera for a scene given none (rad-shade without --view): from outside each side of the
// scene's box looking in, and from inside near each wall looking across, the
// one whose probe rays meet the most patches from their front and the fewest backs (an open
// box from its open side, a closed room from inside).
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
    std::string where;      // "outside, from +z", "inside, towards -x", ...
};

// `aspect` is the image's width over its height. Deterministic; +y is up (the OBJ and glTF
// convention) unless the scene is far flatter along y than along z.
ChosenView choose_view(const radfmt::MeshData& mesh, const RayScene& scene, double aspect);

// A view as the options that give it: "-vp x y z -vd x y z -vu x y z -vh h -vv v".
std::string view_text(const View& view);

} // namespace rad
