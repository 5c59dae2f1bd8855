#include "workflows/demo.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <ostream>

#include "backends/backend.h"
#include "build/demo_scene.h"
#include "build/layout.h"
#include "build/texture_builder.h"
#include "calibrate/fingerprint.h"
#include "common/elapsed_time.h"
#include "common/image_file.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "format/level_image.h"
#include "format/texture_report.h"
#include "gl/headless_context.h"
#include "render/arithmetic_points.h"
#include "render/frame_images.h"
#include "scene/box_room.h"

namespace vt {
namespace {

// Renders the box room from a cache state holding every page, with the oracle and with GL, and
// compares colour and needbuffer.
// Writes frame.png and needbuffer.png into `folder`, naming them in `shown` (the output folder that
// `folder` becomes).
void renderAndCrossCheck(const VirtualTextureReader& reader, const std::filesystem::path& folder,
                         const std::filesystem::path& shown, std::ostream& out) {
  std::vector<uint64_t> pages(reader.storedPageCount());
  for (uint64_t slot = 0; slot < pages.size(); ++slot) pages[slot] = reader.storedPage(slot);
  const auto frames =
      static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(pages.size()))));
  const CacheState cache = makeCacheState(reader, pages, frames, frames);
  RenderSettings settings;
  settings.viewport = {640, 360};
  const ClipSpaceMesh mesh = toClipSpace(boxRoom(), boxRoomCamera(), settings.viewport);

  std::unique_ptr<HeadlessContext> context;
  try {
    context = std::make_unique<HeadlessContext>();
  } catch (const std::exception& e) {
    out << "no OpenGL (" << e.what() << "): the oracle renders alone\n";
  }
  // The oracle follows the GL implementation at hand where a fingerprint confirms a named point
  // (calibrate/fingerprint.h): llvmpipe's arithmetic on llvmpipe.
  if (context) {
    std::string note;
    settings.arithmetic = calibrate::autoModel(context->renderer(), &note).arithmetic;
    if (!note.empty()) out << note << "\n";
  }
  auto start = std::chrono::steady_clock::now();
  const Frame oracle = makeFrameRenderer(Backend::kOracle, cache)->render(mesh, settings);
  const double oracleSeconds = secondsSince(start);
  const auto width = static_cast<uint32_t>(settings.viewport.width),
             height = static_cast<uint32_t>(settings.viewport.height);
  const std::vector<uint8_t> color = colorImage(oracle), need = needImage(oracle, false);
  writeImage8(folder / "frame.png", width, height, 4, std::as_bytes(std::span(color)));
  writeImage8(folder / "needbuffer.png", width, height, 4, std::as_bytes(std::span(need)));
  out << "oracle (profile " << arithmeticLabel(settings.arithmetic) << "): " << width << " x "
      << height << " in " << oracleSeconds * 1000.0 << " ms, wrote "
      << (shown / "frame.png").string() << " and " << (shown / "needbuffer.png").string() << "\n";
  if (!context) return;

  const std::unique_ptr<FrameRenderer> gl = makeFrameRenderer(Backend::kGl, cache);
  start = std::chrono::steady_clock::now();
  const Frame frame = gl->render(mesh, settings);
  const double glSeconds = secondsSince(start);
  size_t colorSame = 0, needSame = 0;
  for (size_t i = 0; i < oracle.need.size(); ++i) {
    needSame += frame.need[i] == oracle.need[i];
    colorSame += std::equal(frame.color.begin() + static_cast<long>(4 * i),
                            frame.color.begin() + static_cast<long>(4 * i + 4),
                            oracle.color.begin() + static_cast<long>(4 * i));
  }
  out << context->renderer() << ": the same frame in " << glSeconds * 1000.0 << " ms\n"
      << "cross-check: colour identical in " << colorSame << " of " << oracle.need.size()
      << " pixels, needbuffer identical in " << needSame << "\n";
}

}  // namespace

void runDemo(const std::filesystem::path& shown, std::ostream& out) {
  // Everything goes into a temporary folder that takes the output's place once complete: a
  // failure leaves the previous output or none. Messages name the files by their final paths.
  TemporaryFolder staging(shown, "scene.vt");
  const std::filesystem::path folder = staging.path();
  auto start = std::chrono::steady_clock::now();
  const std::filesystem::path layoutFile = writeDemoScene(folder / "scene");
  out << "wrote the default scene " << (shown / "scene" / layoutFile.filename()).string() << " in "
      << secondsSince(start) << " s\n";

  const Layout layout = readLayout(layoutFile);
  const std::filesystem::path file = folder / "scene.vt";
  const BuildReport build = buildVirtualTexture(layout, file);
  out << "built " << (shown / "scene.vt").string() << " in " << build.seconds << " s\n";

  start = std::chrono::steady_clock::now();
  const VirtualTextureReader reader(file);
  nlohmann::json report = textureReport(reader);
  report["verified_pages"] = verifyAllPages(reader);
  report["file"] = (shown / "scene.vt").string();
  out << "read and verified in " << secondsSince(start) << " s\n\n"
      << formatTextureReport(report) << '\n';

  const uint32_t level = reader.description().finestLevel() - 1;
  const std::string image = "level" + std::to_string(level) + ".png";
  const LevelImage pixels = assembleLevel(reader, level);
  writeImage8(folder / image, pixels.side, pixels.side, pixels.channels, pixels.texels);
  out << "wrote " << (shown / image).string() << " (level " << level << ", " << pixels.side << " x "
      << pixels.side << " texels)\n\n";
  renderAndCrossCheck(reader, folder, shown, out);
  staging.commit();
}

}  // namespace vt
