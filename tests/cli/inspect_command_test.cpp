// `vt inspect`: the page of a flight holds, per shown frame, the six images, the statistics, the
// head of the priority queue with each page's heuristic terms and the streamed pages; headless
// Chromium steps through it with the keyboard.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "headless_chromium.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

nlohmann::json embeddedData(const std::filesystem::path& page) {
  const std::vector<std::byte> bytes = test::readBytes(page);
  const std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const std::string open = "id=\"inspect-data\">";
  const size_t begin = text.find(open) + open.size();
  return nlohmann::json::parse(text.substr(begin, text.find("</script>", begin) - begin));
}

TEST(InspectCommand, ShowsEveryAskedFrameWithImagesQueueTermsAndStreamedPages) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const auto result = test::runCommand(VT_EXECUTABLE, {"inspect",     (dir / "t.vt").string(),
                                                       "--size",      "96x64",
                                                       "--heuristic", "hotspot*noisevalue",
                                                       "--budget",    "3",
                                                       "--lookahead", "stopfix",
                                                       "--first",     "4",
                                                       "--last",      "24",
                                                       "--every",     "4",
                                                       "--queue",     "8",
                                                       "-o",          (dir / "run.html").string()},
                                       dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("wrote 6 frames of a 51-frame flight"));

  const nlohmann::json data = embeddedData(dir / "run.html");
  ASSERT_EQ(data["frames"].size(), 6u);
  for (size_t f = 0; f < 6; ++f) {
    const nlohmann::json& frame = data["frames"][f];
    SCOPED_TRACE(f);
    EXPECT_EQ(frame["frame"], 4 + 4 * static_cast<int>(f));
    std::vector<std::string> names;
    for (const auto& image : frame["images"]) names.push_back(image["name"]);
    EXPECT_EQ(names,
              (std::vector<std::string>{"rendered", "reference", "difference", "needbuffer (level)",
                                        "resident level", "cache atlas"}));
    EXPECT_LE(frame["queue"].size(), 8u);
    EXPECT_LE(frame["streamed"].size(), 3u);
    // The streamed pages are the head of the queue (budget mode streams in priority order).
    for (size_t s = 0; s < frame["streamed"].size() && s < frame["queue"].size(); ++s) {
      EXPECT_EQ(frame["queue"][s][0], frame["streamed"][s]);
      EXPECT_EQ(frame["queue"][s][5], true);
    }
    // Needed pages carry the heuristic's factors; ancestors (none here) their children's sum.
    if (!frame["queue"].empty()) {
      EXPECT_EQ(frame["terms"], (nlohmann::json{"hotspot", "noisevalue"}));
    }
  }

  VT_REQUIRE_CHROMIUM(chromium);
  const test::CommandResult dom =
      test::dumpDomInChromium(*chromium, dir / "run.html", "#selftest", dir.path());
  ASSERT_EQ(dom.exitCode, 0) << dom.err;
  EXPECT_THAT(dom.out, HasSubstr("selftest ok frames=6"));
}

TEST(InspectCommand, RefusesFramesOutsideThePathAndPagesTooLarge) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
  const auto outside = test::runCommand(
      VT_EXECUTABLE, {"inspect", (dir / "t.vt").string(), "--first", "30", "--last", "60"},
      dir.path());
  EXPECT_EQ(outside.exitCode, 1);
  EXPECT_THAT(outside.err, HasSubstr("frames 30 to 60 do not lie in the path's 0 to 50"));
  EXPECT_FALSE(std::filesystem::exists(dir / "inspect.html"));
}

}  // namespace
}  // namespace vt
