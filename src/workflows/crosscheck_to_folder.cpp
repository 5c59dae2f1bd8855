#include "workflows/crosscheck_to_folder.h"

#include "common/error.h"
#include "common/resource_limits.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "scene/test_scenes.h"
#include "verify/crosscheck_captures.h"
#include "verify/crosscheck_scenes.h"

namespace vt {

void crosscheckToFolder(const CrosscheckRequest& request) {
  if (!request.captures.empty()) {
    if (!crosscheckCaptures({request.captures, request.output, request.model, request.threads,
                             request.allSets, request.shard})
             .passed())
      throw InputError(request.captures,
                       "crosscheck found unexplained pixels or unreadable captures (see " +
                           (request.output / "junit.xml").string() + ")");
    return;
  }
  ScenesCheckOptions options{request.texture, {}, request.viewport, request.model, request.output,
                             request.allSets};
  // Bad input fails here, before any work.
  if (!request.mesh.empty()) {
    const Mesh mesh = loadObjMesh(request.mesh);
    const CameraPath path = CameraPath::load(request.path);
    // Each frame drawn in two modes by two renderers.
    requirePathPixelsFit(
        request.path,
        static_cast<uint64_t>((path.frameCount() + request.every - 1) / request.every),
        static_cast<uint64_t>(options.viewport.width),
        static_cast<uint64_t>(options.viewport.height), 4);
    options.views = flythroughViews(mesh, path, request.every);
  } else {
    options.views = namedSceneViews(request.scenes);
  }
  if (!crosscheckScenes(options).passed())
    throw InputError(request.texture, "crosscheck found unexplained pixels (see " +
                                          (request.output / "summary.json").string() + ")");
}

}  // namespace vt
