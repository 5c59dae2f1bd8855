// `vt inspect`: the page of a flight holds, per shown frame, the six images, the statistics, the
// head of the priority queue with each page's heuristic terms and the streamed pages; headless
// Chromium steps through it with the keyboard.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
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
    ASSERT_EQ(frame["queues"].size(), 1u);
    const nlohmann::json& queue = frame["queues"][0];
    EXPECT_EQ(queue["label"], "");
    EXPECT_LE(queue["queue"].size(), 8u);
    EXPECT_LE(queue["streamed"].size(), 3u);
    // The streamed pages are the head of the queue (budget mode streams in priority order).
    for (size_t s = 0; s < queue["streamed"].size() && s < queue["queue"].size(); ++s) {
      EXPECT_EQ(queue["queue"][s][0], queue["streamed"][s]);
      EXPECT_EQ(queue["queue"][s][5], true);
    }
    // Needed pages carry the heuristic's factors; ancestors (none here) their children's sum.
    if (!queue["queue"].empty()) {
      EXPECT_EQ(queue["terms"], (nlohmann::json{"hotspot", "noisevalue"}));
    }
  }

  VT_REQUIRE_CHROMIUM(chromium);
  const test::CommandResult dom =
      test::dumpDomInChromium(*chromium, dir / "run.html", "#selftest", dir.path());
  ASSERT_EQ(dom.exitCode, 0) << dom.err;
  EXPECT_THAT(dom.out, HasSubstr("selftest ok frames=6"));
}

// Two configurations side by side: each one's frame, difference, resident levels, statistics and
// queue under its label, and where each is nearer the reference; the second named in a
// configurations file. The pages each streamed are those its own flight streams.
TEST(InspectCommand, ShowsTwoConfigurationsSideBySide) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  std::ofstream(dir / "configs.json") << R"({"defaults": {"budget": 3}, "configurations": [
      {"name": "PixelSum 3"}, {"name": "Gain 3", "ancestors": "gain"}]})";
  const auto result = test::runCommand(
      VT_EXECUTABLE,
      {"inspect", (dir / "t.vt").string(), "--size", "96x64", "--config",
       (dir / "configs.json").string(), "--config-name", "PixelSum 3", "--against",
       (dir / "configs.json").string(), "--against-name", "Gain 3", "--first", "2", "--last", "10",
       "--every", "4", "-o", (dir / "both.html").string()},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("wrote 3 frames of a 51-frame flight"));
  EXPECT_THAT(result.out, HasSubstr("by Gain 3"));
  const nlohmann::json data = embeddedData(dir / "both.html");
  EXPECT_EQ(data["title"], "vt inspect: PixelSum 3 against Gain 3");
  ASSERT_EQ(data["frames"].size(), 3u);
  bool differ = false;
  for (const nlohmann::json& frame : data["frames"]) {
    std::vector<std::string> names;
    for (const auto& image : frame["images"]) names.push_back(image["name"]);
    EXPECT_EQ(names, (std::vector<std::string>{
                         "rendered (PixelSum 3)", "rendered (Gain 3)", "reference",
                         "difference (PixelSum 3)", "difference (Gain 3)",
                         "nearer the reference: PixelSum 3 green, Gain 3 magenta",
                         "needbuffer (level)", "resident level (PixelSum 3)",
                         "resident level (Gain 3)", "cache atlas (PixelSum 3)",
                         "cache atlas (Gain 3)"}));
    ASSERT_EQ(frame["queues"].size(), 2u);
    EXPECT_EQ(frame["queues"][0]["label"], "PixelSum 3");
    EXPECT_EQ(frame["queues"][1]["label"], "Gain 3");
    differ = differ || frame["queues"][0]["streamed"] != frame["queues"][1]["streamed"];
    EXPECT_EQ(frame["statistics"][0][0], "covered pixels (PixelSum 3)");
    EXPECT_EQ(frame["statistics"][1][0], "covered pixels (Gain 3)");
  }
  EXPECT_TRUE(differ) << "the two strategies streamed the same pages in every frame shown";

  const auto unnamed = test::runCommand(
      VT_EXECUTABLE,
      {"inspect", (dir / "t.vt").string(), "--against", (dir / "configs.json").string(),
       "--against-name", "Ceiling 3", "-o", (dir / "none.html").string()},
      dir.path());
  EXPECT_EQ(unnamed.exitCode, 1);
  EXPECT_THAT(unnamed.err, HasSubstr("configs.json: no configuration named 'Ceiling 3' (it holds "
                                     "'PixelSum 3', 'Gain 3')"));
  EXPECT_FALSE(std::filesystem::exists(dir / "none.html"));

  VT_REQUIRE_CHROMIUM(chromium);
  const test::CommandResult dom =
      test::dumpDomInChromium(*chromium, dir / "both.html", "#selftest", dir.path());
  ASSERT_EQ(dom.exitCode, 0) << dom.err;
  EXPECT_THAT(dom.out, HasSubstr("selftest ok frames=3"));
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
