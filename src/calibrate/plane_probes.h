#pragma once
// The plane group of the probe pack: draws that measure how an implementation evaluates its
// attribute and depth planes and stores Z24, with nothing else in the way. The first probes
// (raster_fit.h) are perspective triangles at arbitrary positions, so on a GPU whose arithmetic
// no member reproduces they cannot tell the setup, the evaluation and the vertex values apart
// (data/gpus/nvidia-h100/plane-setup.md, "The probe that would decide"). Here:
//
//   one triangle T with its vertices on the 1/256 grid, w = 1, window depths that are floats
//   (multiples of 2^-24 in [0.25, 1) or near 2^-10) and exact coordinates, so that its window
//   values are the vertex values themselves; drawn alone (the base), shifted by (2^k, 2^k)
//   pixels for k = 0 to 5, in copies shifted by 64, 128, 256 and 512 along x and along y (the
//   evaluation origin: an evaluation at the window origin changes with the shift, one at a vertex
//   does not), with depths near 0.999 and near 2^-10 (large and small terms), with its vertices
//   in the two other rotations (which vertex anchors the planes), and with w = 0.5, 2 and 3 at
//   its vertices (how the vertex depth is computed); all into 32F depth;
//   4,096 squares of 4 x 4 pixels, each at a constant depth, into Z24: the conversion of a
//   window depth known exactly, near the ties of z (2^24 - 1) and between them.
//
// The group comes after the first probes (probes/probe_draws.h, holdsOptionalGroup): a folder
// drawn before it fits as before.
//
// The noperspective group, after the filter group (filter_fit.h): random triangles whose vertices
// lie on the 1/256 grid with window depths that are multiples of 2^-24, and w of 0.5, 1, 2 or 4
// at each vertex, drawn with `noperspective` coordinates. Dividing by a power of two is exact, so
// the oracle draws the same triangles divided through (w = 1, where 1/w is 1 at every pixel and
// the perspective division changes nothing): the implementation's planes and their evaluation
// on triangles of every shape, without its reciprocal or division in the way.

#include <string>
#include <vector>

#include "probes/probe_draws.h"

namespace vt::calibrate {

struct PlaneProbe {
  std::string name;  // "base", "shift 4", "x copies", ... (in findings)
  ClipSpaceMesh mesh;
  Viewport viewport;
  DepthFormat format = DepthFormat::kDepth32F;
  // The copies of T in the mesh, in order (triangle i = copy i), and where each lies: the
  // window offset of its vertices from the base's. Empty for the constant-depth squares.
  std::vector<glm::ivec2> copies;
};

// The group, in the order it is drawn: the 32F draws of T, then the Z24 squares (last).
std::vector<PlaneProbe> planeProbes();

struct NoperspectiveProbe {
  std::string name;       // "small triangles", "large triangles"
  ClipSpaceMesh drawn;    // drawn with noperspective coordinates: w of 0.5 to 4 at its vertices
  ClipSpaceMesh divided;  // the same vertices divided by their w, exactly: w = 1
  Viewport viewport;
};
// The noperspective group, in the order it is drawn: 400 triangles of at most 32 pixels a side,
// then 60 of any size, each in 256 x 256 pixels.
std::vector<NoperspectiveProbe> noperspectiveProbes();

// Whether T's values move with it: every shifted copy of T compared, pixel by pixel, with the
// base copy at the pixel as far back (triangle, coordinates, derivatives and depth bit for bit).
struct ShiftEvidence {
  uint64_t pixels = 0;     // pixels of shifted copies compared
  uint64_t differing = 0;  // of them, those whose values are not the base's
  int smallestShift = 0;   // the smallest shift at which a value changed (0: none changed)
};
// `drawn[i]` is the readback of planeProbes()[i].
ShiftEvidence shiftEvidence(const std::vector<PlaneProbe>& probes,
                            const std::vector<RasterReadback>& drawn);

// "the values of a triangle shifted by 1 to 512 pixels are the base's, bit for bit (...)" or
// "... change from a shift of 2^k (...)".
std::string shiftFinding(const ShiftEvidence& evidence);

}  // namespace vt::calibrate
