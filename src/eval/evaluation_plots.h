#pragma once
// The figures of an evaluation folder, drawn by scripts/evaluation-plots.py (matplotlib), which is
// embedded in the binary at build time and fed to `PYTHON - FOLDER` on stdin (no shell). The
// interpreter: $VT_PYTHON when set; else /usr/bin/python3 when present (Debian's, where
// scripts/install-deps.sh puts python3-matplotlib); else python3 on the PATH.

#include <filesystem>
#include <string>

namespace vt {

// The interpreter drawEvaluationPlots runs, as described above.
std::string plotInterpreter();

// Draws the figures summary.json names into `folder` (STEM.svg and STEM.png each). Throws
// std::runtime_error with one line naming the problem, and `shownAs` (the folder the user asked
// for; `folder` may be its staging copy), when the interpreter cannot be started, matplotlib is
// missing or the script fails.
void drawEvaluationPlots(const std::filesystem::path& folder, const std::filesystem::path& shownAs);

}  // namespace vt
