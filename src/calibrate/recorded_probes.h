#pragma once
// The calibration's draws recorded into a folder or replayed from one (capture/probe_files.h):
// `vt calibrate --record-probes DIR` draws here and records every request with its result;
// `vt-capture probes DIR -o OUT` draws those requests on another machine's implementation; `vt
// calibrate --probes OUT` fits the model from what it drew, without a GL context. The draws are
// asked in a fixed order (no probe depends on a fit), so the replay answers the i-th draw with the
// i-th record after checking that the two requests are the same, bit for bit.

#include <filesystem>

#include "probes/probe_draws.h"

namespace vt::calibrate {

class RecordingProbeDrawer : public ProbeDrawer {
 public:
  explicit RecordingProbeDrawer(std::filesystem::path folder);
  std::vector<glm::vec4> shader(const ShaderProbe& probe) override;
  std::vector<glm::u8vec4> colour(const ShaderProbe& probe) override;
  RasterReadback triangles(const ClipSpaceMesh& mesh, Viewport viewport, DepthFormat format,
                           Interpolation interpolation) override;
  ProbeIdentity identity() override { return identityHere(); }
  std::optional<std::vector<uint32_t>> sweep(const FunctionSweep& sweep) override;
  // Writes probes.json with the number of draws recorded, and sweeps.json with the sweeps.
  void finish();

 private:
  std::filesystem::path folder_;
  size_t next_ = 0;
  std::vector<FunctionSweep> sweeps_;
};

class RecordedProbeDrawer : public ProbeDrawer {
 public:
  // Reads probes.json; throws InputError naming the file when the folder is not a probe folder.
  explicit RecordedProbeDrawer(std::filesystem::path folder);
  std::vector<glm::vec4> shader(const ShaderProbe& probe) override;
  std::vector<glm::u8vec4> colour(const ShaderProbe& probe) override;
  RasterReadback triangles(const ClipSpaceMesh& mesh, Viewport viewport, DepthFormat format,
                           Interpolation interpolation) override;
  ProbeIdentity identity() override { return identity_; }
  // The folder's bc3-alpha.u8 (scripts/bc3-alpha-probe.py table), if it has one; InputError
  // naming it when it is not 65,536 x 6 bytes.
  std::optional<std::vector<uint8_t>> denseAlphaTable() override;
  // The sweep's results, where the folder's sweeps.json asks for it and its file is there;
  // InputError when the folder's sweep of that name asks for other inputs (another version).
  std::optional<std::vector<uint32_t>> sweep(const FunctionSweep& sweep) override;
  // Whether the folder holds the group's draws: false where it ends where the group begins
  // (drawn before the group existed); InputError where it ends inside the group.
  bool holdsGroup(size_t draws) override;

 private:
  std::filesystem::path folder_;
  size_t count_ = 0, next_ = 0;
  ProbeIdentity identity_;
  std::vector<FunctionSweep> sweeps_;  // what the folder's sweeps.json lists
};

}  // namespace vt::calibrate
