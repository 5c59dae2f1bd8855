// vt retexture SCENE -o FOLDER: give every face of a Quake 3 map or an OBJ scene its own area of
// one virtual texture (thesis 3.3.2), write the retextured mesh, the layout for `vt build` and a
// report comparing the thesis's layout with ours.

#include <bit>
#include <iostream>
#include <memory>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "common/output_path.h"
#include "workflows/retexture_to_folder.h"

namespace vt {
void addRetextureCommand(CLI::App& app) {
  struct Options {
    std::string scene, output;
    std::vector<std::string> packages;
    RetextureOptions retexture;
    uint32_t border = 4;
    int patchLevel = kPatchTessellationLevel;
    bool noCoherence = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "retexture", "Give every face of a Quake 3 map or an OBJ scene its own texture area");
  command->add_option("SCENE", o->scene, "A map name (with --packages) or an .obj file")
      ->required();
  command->add_option("-o,--output", o->output, "Folder for the mesh, layout, report and images")
      ->required();
  command->add_option("--packages", o->packages,
                      "Folder of .pk3 archives (repeatable, later folders override)");
  command->add_option("--method", o->retexture.method, "charts (ours) or baseline (the thesis's)")
      ->check(CLI::IsMember({"charts", "baseline"}))
      ->capture_default_str();
  command->add_option("--page-size", o->retexture.pageSize, "Page size P, a power of two")
      ->check(CLI::Range(1u, 1u << 15))
      ->capture_default_str();
  command->add_option("--border", o->border, "Page border B of the layout")->capture_default_str();
  command->add_option("--margin", o->retexture.charts.margin, "Texels around each chart")
      ->check(CLI::Range(0u, 64u))
      ->capture_default_str();
  command
      ->add_option("--chart-slack", o->retexture.charts.slack,
                   "Extra area a merged chart may waste, as a fraction of its parts'")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  command
      ->add_option("--column-pages", o->retexture.charts.columnPages,
                   "Width of the chart layout's packing columns, in pages")
      ->check(CLI::Range(1u, 1u << 15))
      ->capture_default_str();
  command->add_option("--patch-level", o->patchLevel, "Subdivisions per Bezier patch and side")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_flag("--no-coherence", o->noCoherence, "Skip the coherence figure (no rendering)");
  command
      ->add_option("--threads", o->retexture.coherence.threads,
                   "Worker threads of the oracle (0: every core)")
      ->check(workerCount());
  command->callback([o] {
    o->retexture.measureCoherence = !o->noCoherence;
    if (std::popcount(o->retexture.pageSize) != 1)
      throw CLI::ValidationError("--page-size", "must be a power of two");
    const std::filesystem::path output = o->output, scenePath = o->scene;
    const bool obj = scenePath.extension() == ".obj";
    if (!obj && o->packages.empty())
      throw CLI::ValidationError("--packages", "a map needs the folder of its .pk3 archives");
    const std::vector<std::filesystem::path> packages(o->packages.begin(), o->packages.end());
    std::vector<std::filesystem::path> inputs = packages;
    inputs.push_back(scenePath);
    requireOutputFolder(output, inputs);
    retextureToFolder({.scene = scenePath,
                       .obj = obj,
                       .packages = packages,
                       .options = o->retexture,
                       .border = o->border,
                       .patchLevel = o->patchLevel,
                       .output = output},
                      std::cout, std::cerr);
  });
}

}  // namespace vt
