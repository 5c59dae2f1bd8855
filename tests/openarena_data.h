#pragma once
// The real Quake 3 map the tests use, q3dm6ish from OpenArena: scripts/fetch-openarena.sh fetches
// Debian's packages and scripts/test.sh exports VT_OPENARENA_DIR, the folder of their .pk3
// archives. Without it a test is skipped, except in CI (CI=true), where it fails.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "cli/run_command.h"
#include "test_support.h"

namespace vt::test {

inline std::optional<std::filesystem::path> openArenaFolder() {
  const char* folder = std::getenv("VT_OPENARENA_DIR");
  if (folder && std::filesystem::is_directory(folder)) return std::filesystem::path(folder);
  return std::nullopt;
}

// `vt retexture q3dm6ish` into `folder`/q3 and `vt build` of its layout into `folder`/q3.vt. Where
// VT_Q3DM6ISH_DIR names the folder the ctest fixture made them in once for every test
// (tests/openarena/shared_q3dm6ish.sh), links to those instead: the tests only read them.
inline void retextureAndBuildQ3dm6ish(const std::filesystem::path& packages,
                                      const std::filesystem::path& folder) {
  if (const char* shared = std::getenv("VT_Q3DM6ISH_DIR")) {
    const std::filesystem::path made(shared);
    if (std::filesystem::is_directory(made / "q3") &&
        std::filesystem::is_regular_file(made / "q3.vt")) {
      std::filesystem::create_directory_symlink(made / "q3", folder / "q3");
      std::filesystem::create_symlink(made / "q3.vt", folder / "q3.vt");
      return;
    }
  }
  const std::string out = (folder / "q3").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"retexture", "q3dm6ish", "--packages", packages.string(), "-o",
                                 out, "--no-coherence"},
        std::vector<std::string>{"build", out + "/q3dm6ish.layout.json", "-o",
                                 (folder / "q3.vt").string(), "-q"}}) {
    const CommandResult result = runCommand(VT_EXECUTABLE, args, folder);
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  }
}

}  // namespace vt::test

// In a test body: `folder` names the packages' folder, or the test skips (fails in CI).
#define VT_REQUIRE_OPENARENA(folder)                                                          \
  const auto folder = ::vt::test::openArenaFolder();                                          \
  if (!folder) {                                                                              \
    if (::vt::test::runningInCi()) FAIL() << "VT_OPENARENA_DIR is not set in CI";             \
    GTEST_SKIP() << "VT_OPENARENA_DIR not set: run scripts/fetch-openarena.sh and export it"; \
  }
