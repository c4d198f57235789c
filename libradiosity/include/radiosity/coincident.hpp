// Coincident faces (a pass of rad-mesh, after orientation and before imprinting): faces in one
// plane that overlap, not only those with identical corners.
#pragma once
#include "radiosity/scene.hpp"

#include <vector>

namespace rad {

struct CoincidentCase {
    enum Kind {
        kMerged,    // same winding, one wholly inside the other: the inner one is dropped
        kTwins,     // opposite windings, both sides face the scene: a sheet drawn twice, kept
        kWrongCopy, // opposite windings, one side sees backs or nothing: that copy is dropped
        kUndecided, // opposite windings, the rays cannot tell: both kept
    } kind;
    int kept_line = 0, other_line = 0; // the face kept and the other (dropped, or its twin)
    double area = 0;                   // the smaller face's
};
struct CoincidentReport {
    std::vector<CoincidentCase> cases;
    std::vector<std::size_t> kept; // the index before the pass of each face kept, in order
};

// Finds faces whose planes agree (within 1e-6 of the scene's size) and whose outlines overlap
// (one's centroid strictly inside the other). Same winding, one inside the other: one surface,
// the inner copy is dropped. Opposite windings: the two sides of each copied surface (faces of
// one group and material facing one way) cast 64 cosine-weighted rays a face; a side whose rays
// meet fronts of other surfaces faces the scene. Both do: twins, kept (a two-sided sheet drawn
// twice). One does, clearly more than the other: the other copy is dropped. Neither: both kept.
CoincidentReport resolve_coincident_faces(Scene& scene);

} // namespace rad
