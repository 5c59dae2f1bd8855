#pragma once
// `vt golden check`'s work as one call: the precision model resolved for the implementation that
// draws (`auto`: workflows/auto_model.h; a model file from another driver is warned about),
// the golden set flown again and compared (eval/golden.h), one line per failed frame and the
// verdict; InputError naming the golden folder when a frame fails.

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "backends/backend.h"
#include "common/shard.h"
#include "eval/golden.h"

namespace vt {

struct GoldenCheckRequest {
  std::filesystem::path golden, texture, mesh, path;
  Backend backend = Backend::kOracle;
  std::string model = "auto";  // a shipped model's name, a model file, or auto
  std::filesystem::path output;
  std::optional<Shard> shard =
      std::nullopt;  // check only this part of the frames (eval/golden_report.h)
};

GoldenCheck checkGoldenSet(const GoldenCheckRequest& request, std::ostream& out, std::ostream& err);

}  // namespace vt
