// vt render TEXTURE: one frame of a scene with the CPU oracle or the GL path, to images, with its
// run time and, given a reference image, its error.

#include <iostream>
#include <memory>

#include "backends/backend.h"
#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/output_path.h"
#include "render/arithmetic_points.h"
#include "scene/box_room.h"
#include "scene/obj_mesh.h"
#include "workflows/render_one_frame.h"

namespace vt {

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
    renderOneFrame(
        reader,
        RenderRequest{.mesh = o->mesh.empty() ? boxRoom() : loadObjMesh(o->mesh),
                      .camera = o->camera.empty() ? boxRoomCamera() : parseCamera(o->camera),
                      .settings = settings,
                      .backend = backend,
                      .residentLevels = o->residentLevels,
                      .everyPage = o->everyPage,
                      .output = o->output,
                      .needbuffer = o->needbuffer,
                      .reference = o->reference},
        std::cout);
  });
}

}  // namespace vt
