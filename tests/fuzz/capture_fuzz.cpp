// Fuzz target: capture manifests (<vt/oracle/capture.h>) read next to fixed data files, and every
// capture that reads drawn and compared by the oracle (cache states, encodings and counts as the
// manifest gives them; the texture is the fixture's, whatever the manifest names).

#include <stdlib.h>

#include <fstream>
#include <string>
#include <vector>

#include "build/synthetic_texture.h"
#include "common/image_file.h"
#include "common/posix_file.h"
#include "fuzz/fuzz_targets.h"
#include "vt/oracle.h"

namespace vt::fuzz {
namespace {

// The data files every manifest may name, in a folder made once per process:
//   t.vt       a synthetic texture: P = 8, B = 1, levels 0..3, RGBA
//   v.f32      six clip-space vertices, two triangles covering the 4 x 4 viewport
//   i.u32      their indices 0..5
//   c.png      the colour, RGBA8 4 x 4;  n.png  an 8-bit needbuffer, RGBA8 4 x 4
//   n.u32      a 32-bit needbuffer, 4 x 4 x 4 uint32
// tests/fuzz/regressions/capture holds manifests that name them.
struct Fixture {
  std::filesystem::path folder;
  oracle::Texture texture = open();

  oracle::Texture open() {
    std::string name = (std::filesystem::temp_directory_path() / "vt-fuzz-capture-XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) throw std::runtime_error("fuzz: cannot make a folder");
    folder = name;
    writeSyntheticTexture(folder / "t.vt", {{.pageSize = 8, .border = 1, .levelCount = 4, .channels = 4},
                                            std::nullopt});
    const std::vector<float> vertices = {-1, -1, 0, 1, 0, 0, 1,  -1, 0, 1, 1, 0, 1, 1,  0, 1, 1, 1,
                                         -1, -1, 0, 1, 0, 0, 1,  1,  0, 1, 1, 1, -1, 1, 0, 1, 0, 1};
    const std::vector<uint32_t> indices = {0, 1, 2, 3, 4, 5};
    writeFileAtomically(folder / "v.f32", std::as_bytes(std::span(vertices)));
    writeFileAtomically(folder / "i.u32", std::as_bytes(std::span(indices)));
    std::vector<uint8_t> rgba(4 * 4 * 4, 200);
    writeImage8(folder / "c.png", 4, 4, 4, std::as_bytes(std::span(rgba)));
    writeImage8(folder / "n.png", 4, 4, 4, std::as_bytes(std::span(rgba)));
    const std::vector<uint32_t> need(4 * 4 * 4, 1);
    writeFileAtomically(folder / "n.u32", std::as_bytes(std::span(need)));
    return oracle::Texture::open(folder / "t.vt");
  }
};

}  // namespace

void captureManifest(Input input) {
  static Fixture fixture;
  const std::filesystem::path manifest = fixture.folder / "frame.json";
  {
    std::ofstream out(manifest, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(input.data()), static_cast<std::streamsize>(input.size()));
  }
  try {
    oracle::Capture capture = oracle::readCapture(manifest);
    capture.textureIdentity = fixture.texture.identity();
    (void)oracle::checkCapture(capture, fixture.texture, oracle::Profile::kExact, 1);
  } catch (const oracle::Error& e) {
    throw InputError(manifest, e.what());
  }
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::captureManifest)
