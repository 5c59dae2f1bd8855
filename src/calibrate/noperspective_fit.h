#pragma once
// The plane families fitted from the noperspective group (plane_probes.h): where the folder holds
// it, the oracle draws the group's divided meshes in every combination of plane setup, plane
// positions and plane evaluation, with the other members of the arithmetic taken from the
// perspective probes (raster_fit.h). A combination's mismatches are the pixels whose triangle,
// coordinates, derivatives or depth differ in a bit. The perspective division is not in the way
// (1/w is 1 at every pixel of the divided meshes), so on an implementation whose perspective
// coordinates no member reproduces, this tells whether its planes and their evaluation are
// reproduced all the same, and by which members.
//
// Evidence only: the model's members are those the perspective probes chose.

#include <optional>

#include "calibrate/family_fit.h"
#include "render/arithmetic.h"

namespace vt::calibrate {

// Draws the group where the drawer holds it (none where the folder ends before it). `chosen`: the
// arithmetic the other fits took.
std::optional<ParameterFit> fitNoperspectivePlanes(const Arithmetic& chosen);

}  // namespace vt::calibrate
