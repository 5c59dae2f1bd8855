// Fuzz target: .pk3 archives (scene/package_files.h) with their shader scripts
// (scene/texture_resolver.h, scene/shader_script.h) and maps (scene/bsp_file.h).

#include <string>
#include <vector>

#include "fuzz/fuzz_targets.h"
#include "scene/bsp_file.h"
#include "scene/package_files.h"
#include "scene/texture_resolver.h"

namespace vt::fuzz {

void pk3Archive(Input input) {
  const PackageFiles files =
      PackageFiles::fromMemory("fuzz.pk3", std::vector<uint8_t>(input.begin(), input.end()));
  const TextureResolver resolver(files);
  // Every file: a damaged entry is an InputError of its own, the next one is still read.
  for (const std::string& name : files.list("", "")) {
    resolver.resolve(name);
    try {
      const std::vector<uint8_t> bytes = files.read(name);
      if (packageNameKey(name).ends_with(".bsp")) parseBsp(bytes, files.describe(name));
    } catch (const InputError&) {
    }
  }
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::pk3Archive)
