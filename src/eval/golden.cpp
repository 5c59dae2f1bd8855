#include "eval/golden.h"

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "backends/backend.h"
#include "common/checksum.h"
#include "common/error.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "eval/flight_records.h"
#include "eval/golden_manifest.h"
#include "eval/golden_report.h"
#include "format/virtual_texture_reader.h"
#include "render/arithmetic_points.h"
#include "render/frame_comparison.h"
#include "render/precision_model.h"
#include "scene/obj_mesh.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

uint64_t fileChecksum(const std::filesystem::path& file) {
  const std::string bytes = readTextFile(file, "file");
  return checksum64(std::as_bytes(std::span(bytes)));
}

template <typename T>
uint64_t bytesChecksum(std::span<const T> values) {
  return checksum64(std::as_bytes(values));
}

// The PNG's RGBA8 rows, turned bottom to top like a rendered frame.
std::vector<uint8_t> readGoldenImage(const std::filesystem::path& file, Viewport viewport) {
  requireRegularFile(file, "golden image");
  auto input = OIIO::ImageInput::open(file.string());
  if (!input) throw InputError(file, "cannot read golden image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width != viewport.width || spec.height != viewport.height || spec.nchannels != 4)
    throw InputError(file, "golden image is not " + std::to_string(viewport.width) + " x " +
                               std::to_string(viewport.height) + " RGBA");
  std::vector<uint8_t> rows(static_cast<size_t>(viewport.width) * viewport.height * 4);
  if (!input->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, rows.data()))
    throw InputError(file, "cannot read golden image: " + input->geterror());
  std::vector<uint8_t> flipped(rows.size());
  const size_t stride = static_cast<size_t>(viewport.width) * 4;
  for (int y = 0; y < viewport.height; ++y)
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(y * stride), stride,
                flipped.begin() + static_cast<std::ptrdiff_t>((viewport.height - 1 - y) * stride));
  return flipped;
}

struct Recorded {
  int frame;
  std::vector<uint8_t> color;
  std::vector<glm::uvec4> need;
  FrameQuality quality;
  std::optional<FrameComparison> judged = std::nullopt;  // under a free model
};

// The frames a flight records, and the last it flies (-1: the whole path).
struct RecordedFrames {
  std::function<bool(int frame)> records;
  int last = -1;
};

// Flies `configuration` and keeps the frames `recorded` names.
std::vector<Recorded> flyAndRecord(const VirtualTextureReader& reader, const Mesh& mesh,
                                   const CameraPath& path, const FlightConfiguration& configuration,
                                   Viewport viewport, const Arithmetic& profile,
                                   const RecordedFrames& recorded, Backend backend,
                                   const PrecisionModel* judge = nullptr) {
  FlightOptions options;
  options.settings.viewport = viewport;
  options.settings.arithmetic = profile;
  options.settings.need8 = need8Encodes(reader.description().finestLevel());
  options.backend = backend;
  options.lastFrame = recorded.last;
  const std::function<bool(int)>& records = recorded.records;
  const std::unique_ptr<const ResidentRenderer> everything = makeResidentRenderer(reader);
  // Reference images for the recorded frames only, in the flight's arithmetic as every flight's
  // (frame_plan.h): the quality measures what streaming costs, not the arithmetic.
  options.reference = [&](int frame) {
    return records(frame) ? referenceImage(*everything, mesh, path.at(frame), options.settings)
                          : std::vector<uint8_t>{};
  };
  std::vector<Recorded> kept;
  options.observe = [&](const FlightFrameView& view) {
    if (!records(view.frame)) return;
    kept.push_back({view.frame, std::vector<uint8_t>(view.color.begin(), view.color.end()),
                    std::vector<glm::uvec4>(view.need.begin(), view.need.end()),
                    *view.result.quality});
  };
  // Under a model with free parameters, each recorded frame is drawn again from the cache state
  // it was drawn with (a capture) and judged against the oracle's result sets there.
  std::vector<std::pair<int, FrameComparison>> judged;
  const std::unique_ptr<const CacheRenderer> oracle = makeCacheRenderer();
  if (judge && !judge->pinned()) {
    options.wantsCapture = records;
    options.capture = [&](const FlightCaptureView& view) {
      RenderSettings settings = options.settings;
      applyModel(settings, *judge);
      const Frame drawn = oracle->draw(view.mesh, view.runtime.cacheState(), settings);
      judged.emplace_back(view.frame, compareFrames(drawn, view.color, view.need, settings.need8));
    };
  }
  fly(reader, mesh, path, configuration, options);
  for (auto& [frame, comparison] : judged)
    for (Recorded& r : kept)
      if (r.frame == frame) r.judged = std::move(comparison);
  return kept;
}

}  // namespace

void generateGolden(const GoldenRequest& request, const std::filesystem::path& destination) {
  if (request.every < 1) throw std::invalid_argument("golden: --every must be at least 1");
  const VirtualTextureReader reader(request.texture);
  const Mesh mesh = loadObjMesh(request.mesh);
  const CameraPath path = CameraPath::load(request.path);
  requirePathPixelsFit(request.path, static_cast<uint64_t>(path.frameCount()),
                       static_cast<uint64_t>(request.viewport.width),
                       static_cast<uint64_t>(request.viewport.height), 1);
  // The set is written into a temporary folder that replaces `destination` once complete.
  TemporaryFolder staging(destination, "golden.json");
  const std::filesystem::path& folder = staging.path();
  const std::vector<Recorded> recorded = flyAndRecord(
      reader, mesh, path, request.configuration, request.viewport, request.profile,
      {[every = request.every](int frame) { return frame % every == 0; }}, Backend::kOracle);
  GoldenManifest manifest{.texture = request.texture.filename().string(),
                          .textureIdentity = checksumText(reader.identity()),
                          .mesh = request.mesh.filename().string(),
                          .meshChecksum = checksumText(fileChecksum(request.mesh)),
                          .path = request.path.filename().string(),
                          .pathChecksum = checksumText(fileChecksum(request.path)),
                          .configuration = request.configuration,
                          .viewport = request.viewport,
                          .profile = request.profile,
                          .every = request.every,
                          .frames = {}};
  for (const Recorded& r : recorded) {
    writeColorImage(folder / frameImageName(r.frame), request.viewport, r.color);
    manifest.frames.push_back(
        {.frame = r.frame,
         .color = checksumText(bytesChecksum(std::span<const uint8_t>(r.color))),
         .need = checksumText(bytesChecksum(std::span<const glm::uvec4>(r.need))),
         .rmse = r.quality.rmse,
         .ssim = r.quality.ssim,
         .wssim = r.quality.wssim,
         .image = frameImageName(r.frame)});
  }
  writeFileAtomically(folder / "golden.json", manifest.text());
  staging.commit();
}

bool GoldenCheck::passed() const {
  // A golden set holds at least one frame (golden_manifest.cpp); a shard of a check may hold none,
  // and then its part of the job passes.
  for (const GoldenFrameCheck& frame : frames)
    if (!frame.passed) return false;
  return true;
}

namespace {

// The golden's inputs must be the files it was made of, by identity and checksum.
void requireTheGoldensInputs(const GoldenManifest& golden, const VirtualTextureReader& reader,
                             const std::filesystem::path& mesh, const std::filesystem::path& path) {
  if (checksumText(reader.identity()) != golden.textureIdentity)
    throw InputError(reader.path(), "its identity " + checksumText(reader.identity()) +
                                        " is not the golden's " + golden.textureIdentity +
                                        ": the goldens were made from another texture");
  for (const auto& [file, expected] :
       {std::pair{mesh, golden.meshChecksum}, {path, golden.pathChecksum}})
    if (checksumText(fileChecksum(file)) != expected)
      throw InputError(file, "its checksum " + checksumText(fileChecksum(file)) +
                                 " is not the golden's " + expected +
                                 ": the goldens were made from another file");
}

// One recorded frame against its golden: checksums, quality, the image's differences (written to
// `report` as frameNNNN.difference.png when the frame fails) and, under a model with free
// parameters, the verdict of the oracle's result sets.
GoldenFrameCheck compareWithGolden(const GoldenFrame& expected, const Recorded& recorded,
                                   const std::vector<uint8_t>& image, bool exact, Viewport viewport,
                                   const std::filesystem::path& report) {
  GoldenFrameCheck frame;
  frame.frame = expected.frame;
  frame.colorMatches =
      checksumText(bytesChecksum(std::span<const uint8_t>(recorded.color))) == expected.color;
  frame.needMatches =
      checksumText(bytesChecksum(std::span<const glm::uvec4>(recorded.need))) == expected.need;
  frame.qualityMatches = recorded.quality.rmse == expected.rmse &&
                         recorded.quality.ssim == expected.ssim &&
                         recorded.quality.wssim == expected.wssim;
  std::vector<uint8_t> difference(image.size(), 255);
  for (size_t p = 0; p < image.size(); p += 4) {
    int pixelMax = 0;
    for (size_t c = 0; c < 4; ++c) {
      const int d = std::abs(int{image[p + c]} - int{recorded.color[p + c]});
      pixelMax = std::max(pixelMax, d);
      if (c < 3) difference[p + c] = static_cast<uint8_t>(std::min(255, d * 16));
    }
    frame.pixelsDiffering += pixelMax > 0;
    frame.maxColorDifference = std::max(frame.maxColorDifference, pixelMax);
  }
  if (recorded.judged) {
    frame.explained = recorded.judged->explained;
    frame.unexplained = recorded.judged->unexplained;
    frame.ambiguous = recorded.judged->ambiguous;
  }
  frame.passed = exact ? frame.colorMatches && frame.needMatches && frame.qualityMatches
                       : recorded.judged && frame.unexplained == 0;
  if (!frame.passed)
    writeColorImage(
        report /
            std::filesystem::path(frameImageName(frame.frame)).replace_extension(".difference.png"),
        viewport, difference);
  return frame;
}

}  // namespace

GoldenCheck checkGolden(const std::filesystem::path& folder, const std::filesystem::path& texture,
                        const std::filesystem::path& mesh, const std::filesystem::path& path,
                        Backend backend, const std::optional<PrecisionModel>& model,
                        const std::filesystem::path& reportFolder,
                        const std::optional<Shard>& shard) {
  const std::filesystem::path manifestFile = folder / "golden.json";
  const GoldenManifest golden = GoldenManifest::read(manifestFile);
  const Viewport viewport = golden.viewport;
  const VirtualTextureReader reader(texture);
  requireTheGoldensInputs(golden, reader, mesh, path);

  GoldenCheck check;
  check.backend = toString(backend);
  check.profile = model ? model->arithmetic : golden.profile;
  check.model = model ? model->name : arithmeticLabel(golden.profile);
  const CameraPath cameraPath = CameraPath::load(path);
  requirePathPixelsFit(path, static_cast<uint64_t>(cameraPath.frameCount()),
                       static_cast<uint64_t>(viewport.width),
                       static_cast<uint64_t>(viewport.height), 1);
  TemporaryFolder staging(reportFolder, "check.json");  // replaces the report once complete
  // A shard checks one contiguous block of the recorded frames, and flies up to its last.
  const auto [first, end] = shard.value_or(Shard{}).block(golden.frames.size());
  const std::span<const GoldenFrame> mine(golden.frames.data() + first, end - first);
  const auto inMine = [mine](int frame) {
    return std::any_of(mine.begin(), mine.end(),
                       [&](const GoldenFrame& g) { return g.frame == frame; });
  };
  std::vector<Recorded> recorded;
  if (!mine.empty())
    recorded = flyAndRecord(reader, loadObjMesh(mesh), cameraPath, golden.configuration, viewport,
                            check.profile, {inMine, mine.back().frame}, backend,
                            model ? &*model : nullptr);
  const bool exact = !model || model->pinned();
  for (const GoldenFrame& expected : mine) {
    const auto r = std::find_if(recorded.begin(), recorded.end(),
                                [&](const Recorded& x) { return x.frame == expected.frame; });
    if (r == recorded.end())
      throw InputError(manifestFile,
                       "frame " + std::to_string(expected.frame) + " is not on the path");
    const std::vector<uint8_t> image =
        readGoldenImage(pathInside(folder, expected.image, manifestFile.string()), viewport);
    check.frames.push_back(compareWithGolden(expected, *r, image, exact, viewport, staging.path()));
  }
  writeCheckReport(staging.path(), folder, check);
  if (shard)
    writeGoldenCheckShard(staging.path(), golden, {folder, texture, mesh, path}, *shard, check);
  staging.commit();
  return check;
}

}  // namespace vt
