#pragma once
// Clip-space geometry from GPU captures where a bound of the oracle's result sets once failed:
// regression geometry for the probes of `vt calibrate` (calibrate/raster_fit.cpp) and the
// stability tests. A viewport only changes which pixel centres sample it.

#include "scene/clip_space_mesh.h"

namespace vt {

// The two triangles of the hostile scene's frame 56 at 640 x 400 (scripts/stress-scene.py), each
// with a vertex behind the camera: a small one (w = -56.8), drawn first, and a ground plane
// 2 x 10^5 wide (w = -36,391). At (310, 12) the small one is nearer by 3,900 units of 2^-23 in
// double, and an H100 showed the ground (data/gpus/nvidia-h100/README.md).
ClipSpaceMesh groundUnderATriangleBehindTheCamera();

}  // namespace vt
