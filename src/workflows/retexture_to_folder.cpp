#include "workflows/retexture_to_folder.h"

#include <iomanip>
#include <optional>

#include "common/posix_file.h"
#include "retexture/retexture_outputs.h"
#include "scene/obj_scene.h"

namespace vt {
namespace {

void printMethod(std::ostream& out, const char* label, const MethodResult& method) {
  out << "  " << std::left << std::setw(9) << label << std::right << " side " << method.layout.side
      << ", " << method.quality.finestPages << " finest pages (" << method.quality.allPages
      << " all levels), " << std::fixed << std::setprecision(1)
      << 100.0 * method.quality.referencedFraction << "% of their texels referenced";
  if (method.coherence)
    out << ", " << std::setprecision(2) << method.coherence->pagesPer1000Pixels
        << " pages per 1000 pixels";
  out << std::defaultfloat << '\n';
}

}  // namespace

void retextureToFolder(const RetextureRequest& request, std::ostream& out, std::ostream& err) {
  const std::optional<PackageFiles> files =
      request.obj ? std::nullopt : std::optional(PackageFiles::fromFolders(request.packages));
  const std::string name =
      request.obj ? request.scene.stem().string() : quake3MapName(*files, request.scene.string());
  // Everything, extracted images included, is written into a temporary folder that takes the
  // output's place once complete: a failure leaves the previous output or none. A previous
  // output is recognised by its report.
  TemporaryFolder staging(request.output, name + ".report.json");
  const std::filesystem::path folder = staging.path(), images = folder / "images";
  const TexturedScene scene = request.obj ? loadObjScene(request.scene, images)
                                          : loadQuake3Map(*files, request.scene.string(), images,
                                                          {.patchLevel = request.patchLevel});
  for (const std::string& warning : scene.warnings)
    err << "warning: " << scene.name << ": " << warning << '\n';
  const RetextureResult result = retexture(scene, request.options);
  const MethodResult& chosen = result.chosen(request.options);
  writeRetexturedObj(folder / (scene.name + ".obj"), scene, result.uvs);
  writeRetextureLayout(folder / (scene.name + ".layout.json"), scene, chosen.layout,
                       {.border = request.border});
  writeRetextureReport(folder / (scene.name + ".report.json"), scene, result, request.options);
  writeViewpointTour(folder / (scene.name + ".path.json"), scene);
  staging.commit();
  out << "retextured " << scene.name << ": " << scene.faces.size() << " faces (" << scene.patchFaces
      << " patches), " << scene.textures.size() << " textures, " << scene.skipped.total()
      << " faces skipped; wrote " << request.options.method << " layout to "
      << (request.output / (scene.name + ".layout.json")).string() << '\n';
  printMethod(out, "baseline", result.baseline);
  printMethod(out, "charts", result.charts);
}

}  // namespace vt
