#include "eval/inspect_page.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "common/error.h"
#include "headless_chromium.h"
#include "openarena_data.h"
#include "test_support.h"

namespace vt {
namespace {

std::vector<uint8_t> bytesOf(std::string_view text) { return {text.begin(), text.end()}; }

std::string readText(const std::filesystem::path& path) {
  const std::vector<std::byte> bytes = test::readBytes(path);
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// A pattern in every channel, alpha included, that differs from frame to frame.
InspectImage pattern(const std::string& name, int width, int height, int seed) {
  InspectImage image{name, width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
  for (size_t i = 0; i < image.rgba.size(); ++i)
    image.rgba[i] = static_cast<uint8_t>((i * 37 + size_t(seed) * 101) % 256);
  return image;
}

// Frame f has f + 2 requests, every second one streamed, and three images of odd sizes.
InspectRun exampleRun(int frameCount) {
  InspectRun run{"q3dm6ish </script><script>document.body.remove()</script> <!-- & \"quotes\"",
                 {{"texture", "q3.vt"}, {"cache", "32 x 32 pages"}, {"upload", "4 pages/frame"}},
                 {}};
  for (int f = 0; f < frameCount; ++f) {
    InspectFrame frame;
    frame.frame = 100 + f;
    frame.statistics = {{"resident pages", std::to_string(40 + f)}, {"misses", "3"}};
    frame.images = {pattern("rendered", 16, 12, f), pattern("difference", 8, 8, f + 7),
                    pattern("needbuffer", 5, 3, f + 13)};
    InspectQueue queue;
    for (int r = 0; r < f + 2; ++r) {
      InspectRequest request{uint64_t(1000 + r), uint32_t(r % 3),
                             uint32_t(r),        uint32_t(2 * r),
                             100.0 / (r + 1),    {{"pixelsum", 812.0 - r}, {"noisevalue", 0.3}},
                             r % 2 == 0};
      if (request.streamed) queue.streamed.push_back(request.page);
      queue.queue.push_back(request);
    }
    frame.queues.push_back(queue);
    run.frames.push_back(frame);
  }
  return run;
}

// The JSON between <script type="application/json" id="inspect-data"> and its </script>.
nlohmann::json embeddedData(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"inspect-data\">";
  const size_t begin = page.find(open);
  EXPECT_NE(begin, std::string::npos);
  const size_t end = page.find("</script>", begin);
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

TEST(InspectPage, Base64MatchesTheRfc4648Vectors) {
  // RFC 4648 section 10.
  EXPECT_EQ(encodeBase64(bytesOf("")), "");
  EXPECT_EQ(encodeBase64(bytesOf("f")), "Zg==");
  EXPECT_EQ(encodeBase64(bytesOf("fo")), "Zm8=");
  EXPECT_EQ(encodeBase64(bytesOf("foo")), "Zm9v");
  EXPECT_EQ(encodeBase64(bytesOf("foob")), "Zm9vYg==");
  EXPECT_EQ(encodeBase64(bytesOf("fooba")), "Zm9vYmE=");
  EXPECT_EQ(encodeBase64(bytesOf("foobar")), "Zm9vYmFy");
  // The last two letters of the alphabet and every bit set.
  EXPECT_EQ(encodeBase64(std::vector<uint8_t>{0xfb, 0xff, 0xbf}), "+/+/");
  EXPECT_EQ(encodeBase64(std::vector<uint8_t>{0xff}), "/w==");
}

TEST(InspectPage, PngDecodesToTheSamePixels) {
  const InspectImage image = pattern("odd", 7, 5, 3);
  std::vector<uint8_t> png = encodePng(image);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(std::string(png.begin(), png.begin() + 8), "\x89PNG\r\n\x1a\n");

  test::ScratchDirectory scratch;
  test::writeBytes(
      scratch / "image.png",
      std::vector<std::byte>(reinterpret_cast<const std::byte*>(png.data()),
                             reinterpret_cast<const std::byte*>(png.data()) + png.size()));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // read alpha as stored, not premultiplied
  auto reader = OIIO::ImageInput::open((scratch / "image.png").string(), &config);
  ASSERT_TRUE(reader) << OIIO::geterror();
  const OIIO::ImageSpec& spec = reader->spec();
  EXPECT_EQ(spec.width, 7);
  EXPECT_EQ(spec.height, 5);
  ASSERT_EQ(spec.nchannels, 4);
  std::vector<uint8_t> decoded(image.rgba.size());
  ASSERT_TRUE(reader->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, decoded.data()))
      << reader->geterror();
  EXPECT_EQ(decoded, image.rgba);
}

TEST(InspectPage, SameInputGivesTheSameBytes) {
  test::ScratchDirectory scratch;
  const InspectRun run = exampleRun(3);
  writeInspectPage(scratch / "a.html", run);
  writeInspectPage(scratch / "b.html", run);
  EXPECT_EQ(test::readBytes(scratch / "a.html"), test::readBytes(scratch / "b.html"));
  EXPECT_EQ(encodePng(run.frames[1].images[0]), encodePng(run.frames[1].images[0]));
}

TEST(InspectPage, RejectsAnEmptyRunAndMisSizedImages) {
  test::ScratchDirectory scratch;
  const auto file = scratch / "page.html";
  try {
    writeInspectPage(file, InspectRun{"empty", {}, {}});
    FAIL() << "an empty run was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), file);
    EXPECT_NE(std::string(error.what()).find("no frames"), std::string::npos) << error.what();
  }

  InspectRun run = exampleRun(3);
  writeInspectPage(file, run);
  const std::vector<std::byte> before = test::readBytes(file);
  run.frames[2].images[1].rgba.pop_back();
  try {
    writeInspectPage(file, run);
    FAIL() << "an image of 255 bytes for 8 x 8 pixels was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what())
                  .find("frame 2: image 'difference': 255 bytes of RGBA, expected 8 x 8 x 4 = 256"),
              std::string::npos)
        << error.what();
  }
  EXPECT_EQ(test::readBytes(file), before) << "a failed write must leave the old page";
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(scratch.path()), {}), 1)
      << "no temporary file may remain";

  EXPECT_THROW(encodePng(InspectImage{"empty", 0, 4, {}}), std::invalid_argument);
  EXPECT_THROW(encodePng(InspectImage{"short", 2, 2, std::vector<uint8_t>(15)}),
               std::invalid_argument);
}

TEST(InspectPage, ScriptEndInTheDataStaysEscaped) {
  test::ScratchDirectory scratch;
  const InspectRun run = exampleRun(3);
  writeInspectPage(scratch / "page.html", run);
  const std::string page = readText(scratch / "page.html");
  // The template's own two script elements end; nothing of the data does.
  size_t ends = 0;
  for (size_t at = page.find("</script"); at != std::string::npos;
       at = page.find("</script", at + 1))
    ++ends;
  EXPECT_EQ(ends, 2u);
  EXPECT_EQ(page.find("<!-- &"), std::string::npos);
  EXPECT_NE(page.find("\\u003c/script>"), std::string::npos);

  const nlohmann::json data = embeddedData(page);
  EXPECT_EQ(data["title"], run.title);
  ASSERT_EQ(data["frames"].size(), 3u);
  const nlohmann::json& frame = data["frames"][2];
  EXPECT_EQ(frame["frame"], 102);
  ASSERT_EQ(frame["queues"].size(), 1u);
  const nlohmann::json& queue = frame["queues"][0];
  EXPECT_EQ(queue["terms"], (nlohmann::json{"pixelsum", "noisevalue"}));
  EXPECT_EQ(queue["queue"].size(), 4u);
  EXPECT_EQ(queue["queue"][1], (nlohmann::json{1001, 1, 1, 2, 50.0, false, 811.0, 0.3}));
  EXPECT_EQ(queue["streamed"], (nlohmann::json{1000, 1002}));
  EXPECT_EQ(frame["images"][0]["src"],
            "data:image/png;base64," + encodeBase64(encodePng(run.frames[2].images[0])));
}

TEST(InspectPage, SelfTestPassesInHeadlessChromium) {
  VT_REQUIRE_CHROMIUM(chromium);
  test::ScratchDirectory scratch;
  const int frameCount = 4;
  writeInspectPage(scratch / "page.html", exampleRun(frameCount));

  const auto started = std::chrono::steady_clock::now();
  const test::CommandResult result =
      test::dumpDomInChromium(*chromium, scratch / "page.html", "#selftest", scratch.path());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_EQ(result.exitCode, 0) << "chromium failed after " << seconds << " s:\n" << result.err;
  EXPECT_NE(result.out.find("selftest ok frames=" + std::to_string(frameCount)), std::string::npos)
      << result.out.substr(std::min(result.out.find("<output"), result.out.size()), 400);
  // The title is shown as text, its markup escaped, and the page was not removed by it.
  EXPECT_NE(result.out.find("q3dm6ish &lt;/script&gt;&lt;script&gt;document.body.remove()"),
            std::string::npos);
  EXPECT_NE(result.out.find("data-frames=\"" + std::to_string(frameCount) + "\""),
            std::string::npos);
}

}  // namespace
}  // namespace vt
