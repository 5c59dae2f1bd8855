// vt render TEXTURE: one frame of a scene with the CPU oracle or the GL path, to images, with its
// run time and, given a reference image, its error.

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <iostream>
#include <memory>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/image_file.h"
#include "common/input_file.h"
#include "common/output_path.h"
#include "eval/image_metrics.h"
#include "render/arithmetic_points.h"
#include "backends/backend.h"
#include "render/frame_images.h"
#include "scene/box_room.h"
#include "scene/obj_mesh.h"
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

void addRenderCommand(CLI::App& app) {
  struct Options {
    std::string texture, mesh, camera, size = "640x360", profile = "exact", depth = "32f";
    std::string output = "frame.png", needbuffer, reference, backend = "oracle";
    bool bilinear = false, hardwareFilter = false, need8 = false, everyPage = false;
    int residentLevels = -1;
    unsigned threads = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("render", "Render one frame with the CPU oracle");
  command->add_option("TEXTURE", o->texture, "Virtual-texture file (.vt)")->required();
  command->add_option("--mesh", o->mesh,
                      "OBJ mesh with virtual texture coordinates (default: the box room)");
  command->add_option("--camera", o->camera, "x,y,z:tx,ty,tz[:fov] (default: the box room's)")
      ->check(cameraValidator());
  command->add_option("--size", o->size, "WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
  command->add_option("--profile", o->profile, "Precision profile")
      ->check(CLI::IsMember(arithmeticPointNames()))
      ->capture_default_str();
  command->add_option("--depth", o->depth, "Depth buffer format")
      ->check(CLI::IsMember({"24", "32f"}))
      ->capture_default_str();
  command->add_flag("--bilinear", o->bilinear, "Bilinear at the needed level instead of trilinear");
  command->add_flag("--hardware-filter", o->hardwareFilter,
                    "GL_LINEAR sampling instead of texel fetches");
  command->add_flag("--need8", o->need8, "8-bit needbuffer encoding");
  CLI::Option* levels =
      command
          ->add_option("--resident-levels", o->residentLevels,
                       "Only levels 0..K-1 resident (a cache state); default the levels an "
                       "8192^2 cache texture holds, coarsest first")
          ->check(CLI::Range(1, 16));
  command
      ->add_flag("--every-page", o->everyPage,
                 "Every stored page resident, read from the file as the frame needs it, also "
                 "where they exceed a cache texture (the oracle only)")
      ->excludes(levels);
  command->add_option("--threads", o->threads, "Worker threads of the oracle (0: every core)")
      ->check(workerCount());
  command
      ->add_option("--backend", o->backend, "oracle (the CPU reference) or gl (OpenGL, headless)")
      ->check(CLI::IsMember({"oracle", "gl"}))
      ->capture_default_str();
  command->add_option("-o,--output", o->output, "Colour image")->capture_default_str();
  command->add_option("--needbuffer", o->needbuffer, "Needbuffer image, coloured by level");
  command->add_option("--reference", o->reference,
                      "Reference image: print RMSE and SSIM against it");
  command->callback([o] {
    const Backend backend = parseBackend(o->backend);
    if (o->everyPage && !drawsEveryPage(backend))
      throw CLI::ValidationError("--every-page",
                                 "the GL path draws from a cache texture; use --backend oracle");
    const std::vector<std::filesystem::path> inputs = {o->texture, o->mesh, o->reference};
    requireOutputFile(o->output, inputs);
    if (!o->needbuffer.empty()) requireOutputFile(o->needbuffer, inputs);
    if (!o->needbuffer.empty() && std::filesystem::path(o->needbuffer) == o->output)
      throw InputError(o->output, "given as both the colour image and the needbuffer image");
    RenderSettings settings;
    settings.viewport = parseSize(o->size);
    settings.arithmetic = arithmeticPoint(o->profile);
    settings.depthFormat = o->depth == "24" ? DepthFormat::kDepth24 : DepthFormat::kDepth32F;
    settings.trilinear = !o->bilinear;
    settings.exactFilter = !o->hardwareFilter;
    settings.need8 = o->need8;
    settings.threads = o->threads;

    const VirtualTextureReader reader(o->texture);
    if (settings.need8 && !need8Encodes(reader.description().finestLevel()))
      throw InputError(o->texture, "the 8-bit needbuffer holds at most 4096 pages per side");
    const Mesh mesh = o->mesh.empty() ? boxRoom() : loadObjMesh(o->mesh);
    const Camera camera = o->camera.empty() ? boxRoomCamera() : parseCamera(o->camera);
    const ClipSpaceMesh clip = toClipSpace(mesh, camera, settings.viewport);

    // One set of defaults whatever the backend: both draw from the same cache state, the levels
    // asked for or the levels an 8192^2 cache texture holds (coarsest first), so that the same
    // command line draws the same frame with either. Only the oracle can do without a cache
    // texture: --every-page draws every stored page straight from the file.
    const CacheState cache = cacheOfLevels(reader, o->residentLevels - 1, 8192);
    const BackendContext context(backend);
    const std::unique_ptr<FrameRenderer> renderer =
        o->everyPage ? makeFrameRendererOfEveryPage(backend, reader, cache)
                     : makeFrameRenderer(backend, cache);
    renderer->warmUp(clip, settings);  // GL compiles its shaders: not part of the frame time
    const auto start = std::chrono::steady_clock::now();
    const Frame frame = renderer->render(clip, settings);
    const double milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (const CacheState* drawn = renderer->cache();
        drawn && drawn->residentPages.size() < reader.storedPageCount())
      std::cout << "cache state: " << drawn->residentPages.size() << " of "
                << reader.storedPageCount() << " pages resident\n";

    const NeededPages needed = neededPages(frame.need, settings.need8);
    const std::vector<uint8_t> color = colorImage(frame);
    const auto width = static_cast<uint32_t>(settings.viewport.width),
               height = static_cast<uint32_t>(settings.viewport.height);
    writeImage8(o->output, width, height, 4, std::as_bytes(std::span(color)));
    if (!o->needbuffer.empty()) {
      const std::vector<uint8_t> need = needImage(frame, settings.need8);
      writeImage8(o->needbuffer, width, height, 4, std::as_bytes(std::span(need)));
    }
    std::cout << "rendered " << o->output << ": " << width << " x " << height << " in "
              << milliseconds << " ms (" << renderer->describe(settings) << "), "
              << needed.coveredPixels << " pixels covered, " << needed.pages.size()
              << " distinct pages needed\n";
    if (!o->reference.empty()) {
      const std::vector<uint8_t> expected = readReference(o->reference, settings.viewport);
      const ImageView a{settings.viewport.width, settings.viewport.height, color};
      const ImageView b{settings.viewport.width, settings.viewport.height, expected};
      const SsimOptions gaussian{.window = SsimWindow::kGaussian};
      std::cout << "against " << o->reference << ": RMSE " << rmse(a, b) << " (8-bit units), SSIM "
                << ssim(a, b) << " (8 x 8), " << ssim(a, b, gaussian)
                << " (Gaussian 11 x 11), WSSIM " << wssim(a, b) << ", in " << milliseconds
                << " ms\n";
    }
  });
}

}  // namespace vt
