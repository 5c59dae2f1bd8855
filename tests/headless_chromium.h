#pragma once
// Loads a page in headless Chromium (Debian's package; scripts/install-deps.sh installs it) with a
// URL fragment and returns the DOM after the page's scripts ran. Skips the calling test when
// Chromium is missing, except in CI, where that fails.

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

#include "cli/run_command.h"
#include "test_support.h"

namespace vt::test {

inline std::optional<std::filesystem::path> chromiumBinary() {
  for (const char* candidate : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (std::filesystem::exists(candidate)) return std::filesystem::path(candidate);
  return std::nullopt;
}

// `timeout` ends a hung browser; the virtual time budget lets the page's promises settle before
// the DOM is dumped. A fresh profile folder under `scratch` for every call.
inline CommandResult dumpDomInChromium(const std::filesystem::path& chromium,
                                       const std::filesystem::path& page,
                                       const std::string& fragment,
                                       const std::filesystem::path& scratch) {
  static int profiles = 0;
  const std::filesystem::path profile =
      scratch / ("chromium-profile-" + std::to_string(profiles++));
  return runCommand(
      "/usr/bin/timeout",
      {"120", chromium.string(), "--headless", "--no-sandbox", "--disable-gpu",
       "--disable-background-networking", "--disable-component-update", "--disable-sync",
       "--user-data-dir=" + profile.string(), "--virtual-time-budget=10000", "--dump-dom",
       "file://" + std::filesystem::absolute(page).string() + fragment},
      scratch);
}

}  // namespace vt::test

// In a test body: `binary` names Chromium, or the test skips (fails in CI).
#define VT_REQUIRE_CHROMIUM(binary)                                             \
  const auto binary = ::vt::test::chromiumBinary();                             \
  if (!binary) {                                                                \
    if (::vt::test::runningInCi()) FAIL() << "chromium is not installed in CI"; \
    GTEST_SKIP() << "chromium not found: scripts/install-deps.sh installs it";  \
  }
