#pragma once
// `vt crosscheck`'s work as one call: captures of any renderer judged by the oracle
// (verify/crosscheck_captures.h), or the named scenes or a flythrough of a mesh drawn here by the
// oracle and by GL and compared (verify/crosscheck_scenes.h). InputError naming the captures or
// the texture when a pixel is unexplained.

#include <filesystem>
#include <optional>
#include <string>

#include "common/shard.h"
#include "scene/clip_space_mesh.h"

namespace vt {

struct CrosscheckRequest {
  std::filesystem::path captures;  // captures to judge; else the texture's scenes
  std::filesystem::path texture;
  std::string scenes = "all";        // named scenes, comma-separated (without mesh and path)
  std::filesystem::path mesh, path;  // a flythrough instead (both)
  int every = 8;                     // with a flythrough: every n-th frame
  Viewport viewport{320, 200};
  std::string model = "auto";
  unsigned threads = 0;  // with captures: the oracle's (0: every core)
  bool allSets = false;  // result sets for every pixel, not only where the other frame differs
  std::optional<Shard> shard =
      std::nullopt;  // with captures: the part this run judges (common/shard.h)
  std::filesystem::path output;
};

void crosscheckToFolder(const CrosscheckRequest& request);

}  // namespace vt
