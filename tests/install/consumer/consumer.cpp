// consumer CAPTURES: checks every capture of the folder with the installed oracle, then checks
// that a capture with one needbuffer pixel changed is reported with exactly that pixel, and that
// bad input arrives as vt::oracle::Error. Prints one line per capture; exits 0 when all holds.

#include <vt/oracle.h>

#include <cstdio>
#include <filesystem>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer CAPTURES\n");
    return 2;
  }
  try {
    const auto manifests = vt::oracle::findCaptures(argv[1]);
    if (manifests.empty()) throw vt::oracle::Error("no captures");
    for (const std::filesystem::path& manifest : manifests) {
      const vt::oracle::Capture capture = vt::oracle::readCapture(manifest);
      const vt::oracle::Texture texture = vt::oracle::Texture::open(capture.texture);
      const vt::oracle::Profile profile = vt::oracle::profileForRenderer(capture.renderer);
      // Every pixel's set: another frame than the captured one is compared below.
      const vt::oracle::CaptureCheck check =
          vt::oracle::checkCapture(capture, texture, profile, 0, vt::oracle::SetScope::kEveryPixel);
      std::printf("%s: %llu of %llu pixels identical, %llu unexplained\n",
                  manifest.filename().c_str(),
                  static_cast<unsigned long long>(check.comparison.identical),
                  static_cast<unsigned long long>(check.comparison.pixels),
                  static_cast<unsigned long long>(check.comparison.unexplained));
      if (!check.comparison.passed()) return 1;

      // One needbuffer pixel changed, where the oracle is certain: exactly it is reported.
      std::vector<uint32_t> need = capture.need;
      size_t pixel = 0;
      while (pixel < check.oracle.ambiguous.size() &&
             (check.oracle.ambiguous[pixel] != 0 || capture.color[pixel * 4 + 3] == 0))
        ++pixel;
      if (pixel == check.oracle.ambiguous.size()) continue;
      need[pixel * 4 + 1] ^= 1;
      const vt::oracle::Comparison changed = vt::oracle::compare(check.oracle, capture.color, need);
      const int width = capture.scene.viewport.width;
      if (changed.unexplained != 1 || changed.mismatches.size() != 1 ||
          changed.mismatches[0].x != static_cast<int>(pixel) % width ||
          changed.mismatches[0].y != static_cast<int>(pixel) / width) {
        std::fprintf(stderr, "the changed pixel was not reported alone\n");
        return 1;
      }
    }
    try {
      (void)vt::oracle::Texture::open("missing.vt");
      return 1;
    } catch (const vt::oracle::Error& e) {
      std::printf("missing texture: %s\n", e.what());
    }
    std::printf("consumer: passed\n");
    return 0;
  } catch (const vt::oracle::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
