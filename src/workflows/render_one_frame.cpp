#include "workflows/render_one_frame.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "common/error.h"
#include "common/image_file.h"
#include "common/input_file.h"
#include "eval/image_metrics.h"
#include "render/frame_images.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

std::vector<uint8_t> readReference(const std::filesystem::path& path, Viewport size) {
  requireRegularFile(path, "reference image");
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) throw InputError(path, "cannot read image: " + OIIO::geterror());
  const auto& spec = input->spec();
  if (spec.width != size.width || spec.height != size.height)
    throw InputError(path, "reference is " + std::to_string(spec.width) + " x " +
                               std::to_string(spec.height) + ", the frame " +
                               std::to_string(size.width) + " x " + std::to_string(size.height));
  std::vector<uint8_t> rgba(static_cast<size_t>(size.width) * size.height * 4, 255);
  const int channels = std::min(spec.nchannels, 4);
  std::vector<uint8_t> pixels(static_cast<size_t>(size.width) * size.height *
                              static_cast<size_t>(channels));
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()))
    throw InputError(path, "cannot read image: " + input->geterror());
  for (size_t i = 0; i < static_cast<size_t>(size.width) * size.height; ++i)
    for (int c = 0; c < 4; ++c)
      rgba[i * 4 + static_cast<size_t>(c)] =
          c < channels ? pixels[i * static_cast<size_t>(channels) + static_cast<size_t>(c)]
                       : (c < 3 ? pixels[i * static_cast<size_t>(channels)] : 255);
  return rgba;
}

}  // namespace

void renderOneFrame(const VirtualTextureReader& reader, const RenderRequest& request,
                    std::ostream& out) {
  const RenderSettings& settings = request.settings;
  if (settings.need8 && !need8Encodes(reader.description().finestLevel()))
    throw InputError(reader.path(), "the 8-bit needbuffer holds at most 4096 pages per side");
  const ClipSpaceMesh clip = toClipSpace(request.mesh, request.camera, settings.viewport);

  // One set of defaults whatever the backend: both draw from the same cache state, the levels
  // asked for or the levels an 8192^2 cache texture holds (coarsest first), so that the same
  // command line draws the same frame with either. Only the oracle can do without a cache
  // texture: --every-page draws every stored page straight from the file.
  const CacheState cache = cacheOfLevels(reader, request.residentLevels - 1, 8192);
  const BackendContext context(request.backend);
  const std::unique_ptr<FrameRenderer> renderer =
      request.everyPage ? makeFrameRendererOfEveryPage(request.backend, reader, cache)
                        : makeFrameRenderer(request.backend, cache);
  renderer->warmUp(clip, settings);  // GL compiles its shaders: not part of the frame time
  const auto start = std::chrono::steady_clock::now();
  const Frame frame = renderer->render(clip, settings);
  const double milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (const CacheState* drawn = renderer->cache();
      drawn && drawn->residentPages.size() < reader.storedPageCount())
    out << "cache state: " << drawn->residentPages.size() << " of " << reader.storedPageCount()
        << " pages resident\n";

  const NeededPages needed = neededPages(frame.need, settings.need8);
  const std::vector<uint8_t> color = colorImage(frame);
  const auto width = static_cast<uint32_t>(settings.viewport.width),
             height = static_cast<uint32_t>(settings.viewport.height);
  writeImage8(request.output, width, height, 4, std::as_bytes(std::span(color)));
  if (!request.needbuffer.empty()) {
    const std::vector<uint8_t> need = needImage(frame, settings.need8);
    writeImage8(request.needbuffer, width, height, 4, std::as_bytes(std::span(need)));
  }
  out << "rendered " << request.output.string() << ": " << width << " x " << height << " in "
      << milliseconds << " ms (" << renderer->describe(settings) << "), " << needed.coveredPixels
      << " pixels covered, " << needed.pages.size() << " distinct pages needed\n";
  if (!request.reference.empty()) {
    const std::vector<uint8_t> expected = readReference(request.reference, settings.viewport);
    const ImageView a{settings.viewport.width, settings.viewport.height, color};
    const ImageView b{settings.viewport.width, settings.viewport.height, expected};
    const SsimOptions gaussian{.window = SsimWindow::kGaussian};
    out << "against " << request.reference.string() << ": RMSE " << rmse(a, b)
        << " (8-bit units), SSIM " << ssim(a, b) << " (8 x 8), " << ssim(a, b, gaussian)
        << " (Gaussian 11 x 11), WSSIM " << wssim(a, b) << ", in " << milliseconds << " ms\n";
  }
}

}  // namespace vt
