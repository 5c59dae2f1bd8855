#pragma once
// vt crosscheck --captures DIR: every capture of a folder (<vt/oracle/capture.h>), from any
// renderer, compared with the oracle under a precision profile.

#include <filesystem>
#include <string>

namespace vt {

struct CapturesCheckOptions {
  std::filesystem::path captures, output;
  std::string profile = "auto";  // auto: from each capture's renderer name
  unsigned threads = 0;
};

// Writes summary.json, junit.xml and per frame the colour difference and the pixel classes into
// `output`; prints one line per capture. Returns whether every capture was read and matched.
bool crosscheckCaptures(const CapturesCheckOptions& options);

}  // namespace vt
