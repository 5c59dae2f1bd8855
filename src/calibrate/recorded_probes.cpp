#include "calibrate/recorded_probes.h"

#include <fstream>

#include "calibrate/decoding_fit.h"
#include "capture/probe_files.h"
#include "capture/sweep_files.h"
#include "common/error.h"

namespace vt::calibrate {
namespace {

using capture::ProbeRequest;
using capture::ProbeResult;

ProbeRequest shaderRequest(ProbeRequest::Kind kind, const ShaderProbe& probe) {
  ProbeRequest r;
  r.kind = kind;
  r.shader = probe;
  return r;
}

ProbeRequest trianglesRequest(const ClipSpaceMesh& mesh, Viewport viewport, DepthFormat format,
                              Interpolation interpolation) {
  ProbeRequest r;
  r.kind = ProbeRequest::Kind::kTriangles;
  r.mesh = mesh;
  r.viewport = viewport;
  r.depth = format;
  r.interpolation = interpolation;
  return r;
}

ProbeResult record(const std::filesystem::path& folder, size_t& next, const ProbeRequest& r) {
  ProbeResult result = capture::drawHere(r);
  capture::writeProbeRequest(folder, next, r);
  capture::writeProbeResult(folder, next, r, result);
  ++next;
  return result;
}

ProbeResult replay(const std::filesystem::path& folder, size_t count, size_t& next,
                   const ProbeRequest& r) {
  if (next >= count)
    throw InputError(folder, "holds " + std::to_string(count) +
                                 " probe draws; this vt calibrate asks for more (drawn for "
                                 "another version?)");
  const ProbeRequest recorded = capture::readProbeRequest(folder, next);
  if (!capture::sameRequest(recorded, r))
    throw InputError(folder, "probe draw " + std::to_string(next) +
                                 " is not the one this vt calibrate asks for (drawn for another "
                                 "version?)");
  return capture::readProbeResult(folder, next++, r);
}

}  // namespace

RecordingProbeDrawer::RecordingProbeDrawer(std::filesystem::path folder)
    : folder_(std::move(folder)) {}

std::vector<glm::vec4> RecordingProbeDrawer::shader(const ShaderProbe& probe) {
  return record(folder_, next_, shaderRequest(ProbeRequest::Kind::kShader, probe)).values;
}
std::vector<glm::u8vec4> RecordingProbeDrawer::colour(const ShaderProbe& probe) {
  return record(folder_, next_, shaderRequest(ProbeRequest::Kind::kColour, probe)).bytes;
}
RasterReadback RecordingProbeDrawer::triangles(const ClipSpaceMesh& mesh, Viewport viewport,
                                               DepthFormat format, Interpolation interpolation) {
  return record(folder_, next_, trianglesRequest(mesh, viewport, format, interpolation)).raster;
}
std::optional<std::vector<uint32_t>> RecordingProbeDrawer::sweep(const FunctionSweep& sweep) {
  std::vector<uint32_t> bits = drawFunctionSweepHere(sweep);
  capture::writeSweepResult(folder_, sweep, bits);
  sweeps_.push_back(sweep);
  return bits;
}
void RecordingProbeDrawer::finish() {
  if (!sweeps_.empty()) capture::writeSweepRequests(folder_, sweeps_);
  capture::writeProbeFolder(folder_, {next_, identityHere()});
}

RecordedProbeDrawer::RecordedProbeDrawer(std::filesystem::path folder)
    : folder_(std::move(folder)) {
  const capture::ProbeFolder description = capture::readProbeFolder(folder_);
  count_ = description.count;
  identity_ = description.identity;
  sweeps_ = capture::readSweepRequests(folder_);
}

std::vector<glm::vec4> RecordedProbeDrawer::shader(const ShaderProbe& probe) {
  return replay(folder_, count_, next_, shaderRequest(ProbeRequest::Kind::kShader, probe)).values;
}
std::vector<glm::u8vec4> RecordedProbeDrawer::colour(const ShaderProbe& probe) {
  return replay(folder_, count_, next_, shaderRequest(ProbeRequest::Kind::kColour, probe)).bytes;
}
RasterReadback RecordedProbeDrawer::triangles(const ClipSpaceMesh& mesh, Viewport viewport,
                                              DepthFormat format, Interpolation interpolation) {
  return replay(folder_, count_, next_, trianglesRequest(mesh, viewport, format, interpolation))
      .raster;
}

std::optional<std::vector<uint32_t>> RecordedProbeDrawer::sweep(const FunctionSweep& sweep) {
  for (const FunctionSweep& listed : sweeps_) {
    if (listed.name != sweep.name) continue;
    if (listed != sweep)
      throw InputError(folder_ / "sweeps.json", "sweep " + sweep.name +
                                                    " is not the one this vt calibrate asks for "
                                                    "(drawn for another version?)");
    // Listed means drawn: a folder that lost the results (a transfer cut short) is refused
    // rather than fitted without them.
    std::optional<std::vector<uint32_t>> bits = capture::readSweepResult(folder_, sweep);
    if (!bits)
      throw InputError(folder_ / "sweeps.json",
                       "lists sweep " + sweep.name + ", but its results are not in the folder");
    return bits;
  }
  return std::nullopt;
}

bool RecordedProbeDrawer::holdsGroup(size_t draws) {
  if (next_ == count_) return false;
  if (count_ - next_ < draws)
    throw InputError(folder_, "holds " + std::to_string(count_) +
                                  " probe draws, which ends inside a group of " +
                                  std::to_string(draws) + " from draw " + std::to_string(next_) +
                                  " (a folder cut short?)");
  return true;
}

std::optional<std::vector<uint8_t>> RecordedProbeDrawer::denseAlphaTable() {
  const std::filesystem::path file = folder_ / kDenseAlphaTableName;
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return std::nullopt;
  const uintmax_t size = std::filesystem::file_size(file, error);
  if (error || size != kDenseAlphaTableBytes)
    throw InputError(file, "is not a dense BC3 alpha table: " +
                               (error ? error.message()
                                      : std::to_string(size) + " bytes, not " +
                                            std::to_string(kDenseAlphaTableBytes)));
  std::vector<uint8_t> table(kDenseAlphaTableBytes);
  std::ifstream in(file, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(table.data()), static_cast<std::streamsize>(table.size())))
    throw InputError(file, "cannot be read");
  return table;
}

}  // namespace vt::calibrate
