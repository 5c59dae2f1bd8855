#pragma once
// The probe pack's function sweeps (probes/function_sweeps.h) as files of a probe folder
// (capture/probe_files.h):
//   sweeps.json        {"format": "vt-sweeps", "version": 1, "sweeps": [{"name", "expression",
//                      "first", "count"[, "target": "depth24"]}, ...]}: what to sweep (a
//                      depth sweep names its target); `vt calibrate --record-probes` writes it
//                      with the requests, `vt-capture probes` draws it
//   sweep-NAME.delta   what the implementation returned: "count" little-endian uint32, the first
//                      result's bits, then each result's minus its predecessor's (mod 2^32).
//                      Neighbours of a smooth function differ little, so the file compresses
//                      well (gpu-run.sh gzips it on the GPU machine).
// Every field is checked (an unknown one is refused) and every size against its limit before
// anything is allocated; a file that disagrees is refused with its name.

#include <filesystem>
#include <optional>
#include <vector>

#include "probes/function_sweeps.h"

namespace vt::capture {

// Writes sweeps.json into `folder` (which must exist).
void writeSweepRequests(const std::filesystem::path& folder,
                        const std::vector<calibrate::FunctionSweep>& sweeps);
// The sweeps `folder`'s sweeps.json asks for; none when it has no sweeps.json.
std::vector<calibrate::FunctionSweep> readSweepRequests(const std::filesystem::path& folder);

void writeSweepResult(const std::filesystem::path& folder, const calibrate::FunctionSweep& sweep,
                      const std::vector<uint32_t>& bits);
// The result bits of `sweep` from its file in `folder`; none when the file is missing.
std::optional<std::vector<uint32_t>> readSweepResult(const std::filesystem::path& folder,
                                                     const calibrate::FunctionSweep& sweep);

}  // namespace vt::capture
