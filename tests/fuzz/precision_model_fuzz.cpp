// Fuzz target: precision-model files (render/precision_model_file.h), read, written and read back.

#include <stdexcept>
#include <string>

#include "fuzz/fuzz_files.h"
#include "fuzz/fuzz_targets.h"
#include "render/precision_model_file.h"

namespace vt::fuzz {

void precisionModel(Input input) {
  static const ScratchFolder folder("precision-model");
  const std::filesystem::path file = folder.path() / "model.json",
                              again = folder.path() / "written.json";
  writeBytes(file, textOf(input));
  const std::string written = modelJson(readModelFile(file));
  // What the writer wrote the reader must take (no InputError), and mean the same model.
  writeBytes(again, written);
  PrecisionModel reread;
  try {
    reread = readModelFile(again);
  } catch (const InputError& e) {
    throw std::logic_error(std::string("a written model does not read: ") + e.what());
  }
  if (modelJson(reread) != written)
    throw std::logic_error("a written model reads back as another:\n" + written + "\n" +
                           modelJson(reread));
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::precisionModel)
