#include "workflows/build_texture.h"

#include <vector>

#include "common/output_path.h"

namespace vt {

void buildTexture(const BuildRequest& request, std::ostream& out) {
  requireOutputFile(request.output, {request.input});
  const Layout layout = request.input.extension() == ".json"
                            ? readLayout(request.input, request.overrides)
                            : singleImageLayout(request.input, request.overrides);
  std::vector<std::filesystem::path> images;
  for (const Placement& placement : layout.images) images.push_back(placement.file);
  requireOutputFile(request.output, images);
  const BuildReport report = buildVirtualTexture(layout, request.output, request.options);
  const TextureDescription& d = layout.description;
  out << "built " << request.output.string() << ": " << d.sideTexels() << " x " << d.sideTexels()
      << " texels, levels 0.." << d.finestLevel() << ", " << report.storedPages << " of "
      << report.totalPages << " pages stored, " << report.fileBytes << " bytes, "
      << layout.images.size() << " images, filter " << toString(layout.filter) << ", "
      << toString(d.colorSpace) << ", in " << report.seconds << " s (row rings " << report.ringBytes
      << " bytes";
  if (request.options.ancestorErrors)
    out << "; ancestor errors measured in " << report.ancestorErrorSeconds << " s";
  out << ")\n";
}

}  // namespace vt
