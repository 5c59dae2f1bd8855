// Fuzz target: calibration probe folders (capture/probe_files.h) as `vt calibrate --probes` reads
// them (calibrate/recorded_probes.h: probes.json, then per draw its request and its result), the
// request and the result written back and read again; and the probe pack's sweeps
// (capture/sweep_files.h: sweeps.json and each sweep's results), written back the same.

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

#include "capture/probe_files.h"
#include "capture/sweep_files.h"
#include "fuzz/fuzz_files.h"
#include "fuzz/fuzz_targets.h"

namespace vt::fuzz {
namespace {

// The files an input may write (fuzz_targets.h): the folder's description, the data files of
// draw 0 and the sweeps' files. Any other name is skipped, so that no input writes outside the
// folder.
constexpr std::array<std::string_view, 11> kDataFiles = {
    "inputs.f32",   "texels.rgba8",     "blocks.bc1",      "blocks.bc3",
    "vertices.f32", "indices.u32",      "result",          "probes.json",
    "sweeps.json",  "sweep-log2.delta", "sweep-sqrt.delta"};
// Files of the folder itself rather than of draw 0.
bool folderFile(std::string_view name) {
  return name == "probes.json" || name == "sweeps.json" || name.starts_with("sweep-");
}

// probe-0000.json and the sections after it written into `folder`.
void writeFolder(std::string_view text, const std::filesystem::path& folder) {
  const std::string separator = std::string("\n") + kProbeFileSeparator;
  size_t end = text.find(separator);
  writeBytes(folder / "probe-0000.json", text.substr(0, end));
  while (end != std::string_view::npos) {
    const size_t nameBegin = end + separator.size();
    const size_t nameEnd = text.find('\n', nameBegin);
    if (nameEnd == std::string_view::npos) return;
    const std::string_view name = text.substr(nameBegin, nameEnd - nameBegin);
    end = text.find(separator, nameEnd);
    const std::string_view bytes =
        text.substr(nameEnd + 1, end == std::string_view::npos ? end : end - nameEnd - 1);
    if (std::find(kDataFiles.begin(), kDataFiles.end(), name) == kDataFiles.end()) continue;
    writeBytes(folder / (folderFile(name) ? std::string(name) : "probe-0000." + std::string(name)),
               bytes);
  }
}

std::string readAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

void probeFolder(Input input) {
  static const ScratchFolder folder("probes"), written("probes-written");
  folder.clear();
  written.clear();
  writeFolder(textOf(input), folder.path());

  try {
    capture::readProbeFolder(folder.path());
  } catch (const InputError&) {
    // A folder without a good probes.json is refused whole; its draws are read all the same.
  }
  try {
    for (const calibrate::FunctionSweep& sweep : capture::readSweepRequests(folder.path())) {
      const auto bits = capture::readSweepResult(folder.path(), sweep);
      if (!bits) continue;
      capture::writeSweepResult(written.path(), sweep, *bits);
      const std::string file = "sweep-" + sweep.name + ".delta";
      if (readAll(written.path() / file) != readAll(folder.path() / file))
        throw std::logic_error("a sweep's results are written back with other bytes");
    }
  } catch (const InputError&) {
    // Sweeps that do not read leave the draw to be read all the same.
  }
  const capture::ProbeRequest request = capture::readProbeRequest(folder.path(), 0);
  const capture::ProbeResult result = capture::readProbeResult(folder.path(), 0, request);

  // The replay compares requests bit for bit (sameRequest): a request that reads must survive
  // being written, and so must its result.
  capture::writeProbeRequest(written.path(), 0, request);
  try {
    if (!capture::sameRequest(capture::readProbeRequest(written.path(), 0), request))
      throw std::logic_error("a written probe request reads back as another");
  } catch (const InputError& e) {
    throw std::logic_error(std::string("a written probe request does not read: ") + e.what());
  }
  capture::writeProbeResult(written.path(), 0, request, result);
  if (readAll(written.path() / "probe-0000.result") != readAll(folder.path() / "probe-0000.result"))
    throw std::logic_error("a probe result is written back with other bytes");
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::probeFolder)
