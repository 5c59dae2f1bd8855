#include "workflows/check_golden_set.h"

#include <optional>

#include "common/error.h"
#include "render/precision_model.h"
#include "render/precision_model_file.h"
#include "workflows/auto_model.h"

namespace vt {

GoldenCheck checkGoldenSet(const GoldenCheckRequest& request, std::ostream& out,
                           std::ostream& err) {
  const BackendContext context(request.backend);
  // auto: the model the implementation's fingerprint confirms (workflows/auto_model.h); the
  // oracle, which has none, flies in the golden set's own profile.
  std::string note;
  const std::optional<PrecisionModel> model =
      request.model == "auto" ? autoModel(context, &note)
                              : std::optional(resolveModel(request.model, context.renderer()));
  if (!note.empty()) err << "vt golden check: " << note << "\n";
  if (model)
    if (const std::string warning =
            calibrationMismatch(*model, context.renderer(), context.version());
        !warning.empty())
      err << "vt golden check: " << warning << "\n";
  const GoldenCheck result =
      checkGolden(request.golden, request.texture, request.mesh, request.path, request.backend,
                  model, request.output, request.shard);
  size_t passed = 0;
  for (const GoldenFrameCheck& frame : result.frames) {
    passed += frame.passed;
    if (!frame.passed)
      out << "frame " << frame.frame << ": colour " << (frame.colorMatches ? "same" : "differs")
          << ", needbuffer " << (frame.needMatches ? "same" : "differs") << ", metrics "
          << (frame.qualityMatches ? "same" : "differ") << "; " << frame.pixelsDiffering
          << " pixels differ from the golden image, by up to " << frame.maxColorDifference << "; "
          << frame.unexplained << " pixels unexplained\n";
  }
  out << "golden check (" << result.backend << ", model " << result.model << "): " << passed
      << " of " << result.frames.size() << " frames pass; wrote "
      << (request.output / "check.json").string() << "\n";
  if (!result.passed())
    throw InputError(request.golden, std::to_string(result.frames.size() - passed) + " of " +
                                         std::to_string(result.frames.size()) +
                                         " golden frames differ (see " +
                                         (request.output / "check.json").string() + ")");
  return result;
}

}  // namespace vt
