// The `vt` executable as a user meets it: reports, exit codes and one-line errors.

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "build/synthetic_texture.h"
#include "build/texture_builder.h"
#include "cli/run_command.h"
#include "common/image_file.h"
#include "format/level_image.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;

class VtCommand : public ::testing::Test {
 protected:
  test::CommandResult vt(const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir_.path());
  }
  std::string sparseTexture() {
    const auto path = dir_ / "sparse.vt";
    writeSyntheticTexture(path,
                          {{.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4}, 0.2});
    return path.string();
  }
  test::ScratchDirectory dir_;
};

TEST_F(VtCommand, InfoPrintsLevelsAndPageCounts) {
  const auto result = vt({"info", sparseTexture()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("virtual texture v1, 4 x unorm8, sRGB, sparse"));
  EXPECT_THAT(result.out, HasSubstr("128 x 128 texels, levels 0..3 (0 coarsest)"));
  EXPECT_THAT(result.out, HasSubstr("25 of 85 pages"));
  EXPECT_THAT(result.out, HasSubstr("    0            16            1            1\n"
                                    "    1            32            4            4\n"
                                    "    2            64           16            4\n"
                                    "    3           128           64           16\n"));
  EXPECT_TRUE(result.err.empty());
}

TEST_F(VtCommand, InfoJsonHoldsTheSameFacts) {
  const auto result = vt({"info", "--json", "--verify", sparseTexture()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto report = nlohmann::json::parse(result.out);
  EXPECT_EQ(report["page_size"], 16);
  EXPECT_EQ(report["border"], 2);
  EXPECT_EQ(report["levels"], 4);
  EXPECT_EQ(report["stored_pages"], 25);
  EXPECT_EQ(report["total_pages"], 85);
  EXPECT_EQ(report["verified_pages"], 25);
  EXPECT_EQ(report["per_level"][3]["stored_pages"], 16);
  EXPECT_THAT(report["identity"].get<std::string>(), MatchesRegex("xxh3:[0-9a-f]{16}"));
}

TEST_F(VtCommand, MalformedFileGivesOneLineAndExitCodeOne) {
  const auto path = sparseTexture();
  auto bytes = test::readBytes(path);
  bytes[16] = std::byte{3};  // page_size 3 (the header checksum is checked after the fields)
  test::writeBytes(dir_ / "bad.vt", bytes);
  const auto result = vt({"info", (dir_ / "bad.vt").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.err, "vt: " + (dir_ / "bad.vt").string() +
                            ": header field page_size: 3 is not a power of two in [1, 4096]\n");
  EXPECT_TRUE(result.out.empty());
}

TEST_F(VtCommand, VerifyFindsACorruptedPage) {
  const auto path = sparseTexture();
  auto bytes = test::readBytes(path);
  bytes[bytes.size() - 100] ^= std::byte{1};  // in the last stored page
  test::writeBytes(dir_ / "corrupt.vt", bytes);
  EXPECT_EQ(vt({"info", (dir_ / "corrupt.vt").string()}).exitCode, 0);  // tables are intact
  const auto result = vt({"info", "--verify", (dir_ / "corrupt.vt").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, MatchesRegex("vt: .*corrupt.vt: page [0-9]+ \\(level 3, x [0-9]+, y "
                                       "[0-9]+\\): checksum mismatch .*\n"));
}

TEST_F(VtCommand, BadArgumentsPrintTheUsageAndExitTwo) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{},
                                               {"info"},
                                               {"info", "a.vt", "--frobnicate"},
                                               {"nonsense"},
                                               {"demo", "--frobnicate"}}) {
    const auto result = vt(args);
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_THAT(result.err, HasSubstr("Usage: vt"));
  }
  EXPECT_THAT(vt({"info"}).err, HasSubstr("Usage: vt info [OPTIONS] FILE"));
}

// Values out of range or grammar are bad arguments too (issue 20, class 8): checked by CLI11
// before any file is read, never blamed on an input, never an allocation sized by them.
TEST_F(VtCommand, BadArgumentValuesPrintTheUsageAndExitTwo) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"fly", "a.vt", "--cache-frames", "0"}, "--cache-frames: '0' is not a whole number from 1"},
      {{"fly", "a.vt", "--heuristic", "pixelsum*bogus"}, "'bogus' is not one of random"},
      {{"fly", "a.vt", "--noise-threshold", "nan"}, "'nan' is not a finite number"},
      {{"fly", "a.vt", "--locked-levels", "99"}, "'99' is not a whole number from 0 to 24"},
      {{"build", "image.png", "-o", "x.vt", "--page-size", "3"},
       "page size '3' is not a power of two in [1, 4096]"},
      {{"build", "image.png", "-o", "x.vt", "--threads", "1000000000"},
       "'1000000000' is not a whole number from 0 to 1024"},
      {{"fly", "a.vt", "--threads", "1000000000"}, "is not a whole number from 0 to 1024"},
      {{"eval", "a.vt", "--jobs", "1000000000"}, "is not a whole number from 0 to 1024"},
      {{"eval", "a.vt", "--heuristic", "pixelsum,bogus"}, "'bogus' is not one of random"},
      {{"eval", "a.vt", "--budget", "5,x"}, "'x' is not a whole number"},
      {{"eval", "a.vt", "--cache-frames", "0"}, "'0' is not a whole number from 1"},
      {{"render", "a.vt", "--size", "4294967360x64"}, "'4294967360x64' is not WIDTHxHEIGHT"},
      {{"render", "a.vt", "--size", "64x-64"}, "is not WIDTHxHEIGHT"},
      {{"render", "a.vt", "--backend", "gl", "--every-page"},
       "--every-page: the GL path draws from a cache texture; use --backend oracle"},
      {{"render", "a.vt", "--resident-levels", "2", "--every-page"},
       "--resident-levels excludes --every-page"},
      {{"build", "image.png", "-o", "x.vt", "--border", "99999"}, "--border: Value 99999"},
      {{"build", "image.png", "-o", "x.vt", "--border", "200"},
       "--border: 200 is not smaller than the page size 128"},
      {{"build", "image.png", "-o", "x.vt", "--side", "1099511627776"},
       "side '1099511627776' is not a power of two"},
      {{"build", "image.png", "-o", "x.vt", "--page-size", "256", "--side", "128"},
       "--side: 128 is not the page size 256 times 2^L"},
      {{"build", "image.png", "-o", "x.vt", "--channels", "17"}, "--channels: Value 17"},
      {{"build", "image.png", "-o", "x.vt", "--format", "bc7"}, "--format: bc7 not in"},
  };
  for (const auto& [args, message] : cases) {
    const auto result = vt(args);
    EXPECT_EQ(result.exitCode, 2) << args[0] << " " << args[args.size() - 2] << ": " << result.err;
    EXPECT_THAT(result.err, HasSubstr(message));
    EXPECT_THAT(result.err, HasSubstr("Usage: vt " + args[0]));
  }
}

TEST_F(VtCommand, HelpAndVersion) {
  const auto version = vt({"--version"});
  EXPECT_EQ(version.exitCode, 0);
  EXPECT_THAT(
      version.out,
      MatchesRegex("vt [0-9]+\\.[0-9]+\\.[0-9]+ \\(virtual-texture file formats 1 to 3\\)\n"));
  for (const char* command : {"build", "info", "demo", "export-level", "render"}) {
    const auto help = vt({command, "--help"});
    EXPECT_EQ(help.exitCode, 0) << command;
    EXPECT_THAT(help.out, HasSubstr("Usage:")) << command;
  }
}

TEST_F(VtCommand, ExportLevelWritesTheAssembledLevel) {
  const auto path = sparseTexture();
  const auto png = (dir_ / "level3.png").string();
  const auto result = vt({"export-level", path, "--level", "3", "-o", png});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  auto input = OIIO::ImageInput::open(png);
  ASSERT_TRUE(input);
  const auto& spec = input->spec();
  ASSERT_EQ(spec.width, 128);
  ASSERT_EQ(spec.nchannels, 4);
  std::vector<std::byte> pixels(128 * 128 * 4);
  ASSERT_TRUE(input->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, pixels.data()));
  EXPECT_EQ(pixels, assembleLevel(VirtualTextureReader(path), 3).texels);

  const auto missing = vt({"export-level", path, "--level", "4", "-o", png});
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_THAT(missing.err, HasSubstr("level 4 does not exist (levels 0..3)"));
}

TEST_F(VtCommand, BuildCompilesALayoutThatInfoAccepts) {
  const std::vector<std::byte> texels(30 * 20 * 3, std::byte{77});
  writeImage8(dir_ / "wall.png", 30, 20, 3, texels);
  std::ofstream(dir_ / "layout.json")
      << R"({"page_size": 16, "border": 2, "images": [{"file": "wall.png", "x": 40, "y": 3}]})";
  const auto output = (dir_ / "out.vt").string();
  const auto result =
      vt({"build", (dir_ / "layout.json").string(), "-o", output, "--threads", "2"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("built " + output + ": 128 x 128 texels, levels 0..3"));
  EXPECT_TRUE(result.err.empty()) << "no progress bar when stderr is not a terminal";
  const auto info = vt({"info", "--verify", output});
  EXPECT_EQ(info.exitCode, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("3 x unorm8, sRGB, sparse"));

  // One image on the command line.
  EXPECT_EQ(vt({"build", (dir_ / "wall.png").string(), "-o", output, "--page-size", "8"}).exitCode,
            0);
  EXPECT_EQ(VirtualTextureReader(output).description().sideTexels(), 32u);
}

// `vt build --ancestor-errors` stores the table (version 3), `vt info` prints its means by
// distance, and `--ancestors gain_ssim` flies with it; a file without the table is refused with
// one line naming it.
TEST_F(VtCommand, BuildStoresAncestorErrorsThatGainSsimFliesWith) {
  const std::vector<std::byte> texels = [] {
    std::vector<std::byte> t(64 * 64 * 3);
    for (size_t k = 0; k < t.size(); ++k) t[k] = std::byte((k * 37 + k / 192 * 11) % 251);
    return t;
  }();
  writeImage8(dir_ / "wall.png", 64, 64, 3, texels);
  const auto output = (dir_ / "errors.vt").string();
  const auto built = vt({"build", (dir_ / "wall.png").string(), "-o", output, "--page-size", "16",
                         "--ancestor-errors"});
  ASSERT_EQ(built.exitCode, 0) << built.err;
  EXPECT_THAT(built.out, HasSubstr("; ancestor errors measured in "));
  const auto info = vt({"info", output});
  EXPECT_THAT(info.out, HasSubstr("virtual texture v3, 3 x unorm8"));
  EXPECT_THAT(info.out, HasSubstr("AncestorErr  mean 1 - SSIM through the ancestor 1 up 0."));
  EXPECT_THAT(info.out, HasSubstr(", 2 up 0."));
  const auto json = nlohmann::json::parse(vt({"info", "--json", output}).out);
  EXPECT_EQ(json["format_version"], 3);
  ASSERT_EQ(json["ancestor_errors"].size(), 2u);
  EXPECT_EQ(json["ancestor_errors"][1]["levels_up"], 2);
  EXPECT_EQ(json["ancestor_errors"][1]["pages"], 16);

  const auto flown = vt({"fly", output, "--size", "96x64", "--ancestors",
                         "gain_ssim", "-o", (dir_ / "flown").string()});
  EXPECT_EQ(flown.exitCode, 0) << flown.err;
  const auto refused = vt({"fly", sparseTexture(), "--size", "96x64",
                           "--ancestors", "gain_ssim", "-o", (dir_ / "refused").string()});
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_THAT(refused.err, MatchesRegex("vt: .*sparse.vt: 'ancestors': 'gain_ssim' needs the "
                                        "ancestor errors that `vt build --ancestor-errors` "
                                        "stores, and this file has none\n"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "refused"));
}

TEST_F(VtCommand, BuildStoresBlockCompressedPages) {
  // A smooth 64 x 64 RGB gradient: BC1 keeps it within a few units.
  std::vector<std::byte> texels(64 * 64 * 3);
  for (size_t i = 0; i < texels.size(); ++i)
    texels[i] = std::byte(static_cast<uint8_t>((i / 3 % 64) * 2 + (i / 192) + (i % 3) * 20));
  writeImage8(dir_ / "wall.png", 64, 64, 3, texels);
  const auto plain = (dir_ / "plain.vt").string(), bc1 = (dir_ / "bc1.vt").string(),
             bc3 = (dir_ / "bc3.vt").string();
  for (const auto& [format, output] : {std::pair{"rgba8", plain}, {"bc1", bc1}, {"bc3", bc3}}) {
    const auto result = vt({"build", (dir_ / "wall.png").string(), "-o", output, "--page-size",
                            "16", "--border", "2", "--format", format});
    ASSERT_EQ(result.exitCode, 0) << result.err;
  }
  EXPECT_THAT(vt({"info", "--verify", plain}).out, HasSubstr("3 x unorm8"));
  const auto info = vt({"info", "--verify", bc1});
  EXPECT_EQ(info.exitCode, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("virtual texture v2, 4 x bc1, sRGB"));
  EXPECT_THAT(info.out, HasSubstr("20^2 stored, 200 bytes each (1600 decoded)"));
  EXPECT_THAT(vt({"info", bc3}).out, HasSubstr("4 x bc3"));
  // 20 x 20 stored texels: 3 bytes each, against 25 blocks of 8 (BC1) or 16 (BC3) bytes.
  const VirtualTextureReader plainReader(plain), bc1Reader(bc1), bc3Reader(bc3);
  EXPECT_EQ(plainReader.description().storedPageBytes(), 1200u);
  EXPECT_EQ(bc1Reader.description().storedPageBytes(), 200u);
  EXPECT_EQ(bc3Reader.description().storedPageBytes(), 400u);
  // The finest level exported from BC1 is the gradient within BC1's error, alpha 255.
  const auto png = (dir_ / "level2.png").string();
  ASSERT_EQ(vt({"export-level", bc1, "--level", "2", "-o", png}).exitCode, 0);
  const LevelImage original = assembleLevel(plainReader, 2), decoded = assembleLevel(bc1Reader, 2);
  ASSERT_EQ(decoded.texels.size() / 4, original.texels.size() / 3);
  int worst = 0;
  for (size_t t = 0; t < decoded.texels.size() / 4; ++t) {
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(static_cast<int>(decoded.texels[t * 4 + c]) -
                                       static_cast<int>(original.texels[t * 3 + c])));
    ASSERT_EQ(decoded.texels[t * 4 + 3], std::byte{255});
  }
  EXPECT_GT(worst, 0);
  EXPECT_LE(worst, 12);  // RGB565 end points (8 levels of 255 in red and blue) and 2-bit indices

  // A border that does not make whole blocks is refused, naming the source and the field.
  const auto odd = vt({"build", (dir_ / "wall.png").string(), "-o", (dir_ / "odd.vt").string(),
                       "--page-size", "16", "--border", "1", "--format", "bc1"});
  EXPECT_EQ(odd.exitCode, 1);
  EXPECT_THAT(odd.err, HasSubstr("wall.png: field border: stored pages of 18 texels (P + 2B) are "
                                 "not whole 4 x 4 blocks of pixel format bc1"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "odd.vt"));
}

TEST_F(VtCommand, BuildPeakMemoryStaysFarBelowTheFinestLevel) {
  if (test::kAddressSanitizer)
    GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine make RSS meaningless";
  // A 16384^2 RGBA texture: its finest level alone is 1 GiB. The process may use what `vt`
  // itself needs (its libraries, measured with --version) plus the documented ring bound plus
  // 32 MiB for pages in flight and the image's scanline.
  const std::vector<std::byte> texels(300 * 200 * 4, std::byte{9});
  writeImage8(dir_ / "tile.png", 300, 200, 4, texels);
  std::ofstream(dir_ / "layout.json") << R"({"side": 16384, "channels": 4,
      "images": [{"file": "tile.png", "x": 5000, "y": 7000}]})";
  const auto build =
      vt({"build", (dir_ / "layout.json").string(), "-o", (dir_ / "big.vt").string()});
  ASSERT_EQ(build.exitCode, 0) << build.err;
  const long baselineKb = vt({"--version"}).maxRssKb;
  const Layout layout = readLayout(dir_ / "layout.json");
  const long boundKb = static_cast<long>(ringBytesBound(layout) / 1024) + 32 * 1024;
  EXPECT_LT(build.maxRssKb - baselineKb, boundKb)
      << "build " << build.maxRssKb << " KB, vt --version " << baselineKb << " KB";
  EXPECT_LT(boundKb, 1024 * 1024 / 16);
}

TEST_F(VtCommand, FlyStreamsTheDefaultPathWithTheSameBytesForAnyThreadCount) {
  const auto texture = sparseTexture();
  const auto fly = [&](const std::string& threads, const std::string& out) {
    return vt({"fly", texture, "--size", "96x64", "--budget", "3", "--cache-frames", "5",
               "--ancestors", "extern", "--heuristic", "pixelsum*noisevalue", "--threads", threads,
               "-o", (dir_ / out).string()});
  };
  const auto one = fly("1", "one"), two = fly("2", "two");
  ASSERT_EQ(one.exitCode, 0) << one.err;
  ASSERT_EQ(two.exitCode, 0) << two.err;
  EXPECT_THAT(one.out, HasSubstr("flew 51 frames"));
  const auto csv = test::readBytes(dir_ / "one" / "frames.csv");
  EXPECT_EQ(csv, test::readBytes(dir_ / "two" / "frames.csv"));
  EXPECT_EQ(test::readBytes(dir_ / "one" / "summary.json"),
            test::readBytes(dir_ / "two" / "summary.json"));
  // The budget holds: no frame streams more than 3 pages.
  const test::CsvTable frames = test::readCsv(dir_ / "one" / "frames.csv");
  for (size_t f = 0; f < frames.rows.size(); ++f) {
    ASSERT_EQ(frames.rows[f].size(), 10u);
    EXPECT_LE(std::stoi(frames.at(f, "streamed")), 3) << "frame " << f;
  }
  EXPECT_EQ(frames.rows.size(), 51u);
  const auto bad =
      vt({"fly", texture, "--heuristic", "pixelsum*speed", "-o", (dir_ / "bad").string()});
  EXPECT_EQ(bad.exitCode, 2);  // a bad argument (issue 20): the usage line too
  EXPECT_THAT(bad.err, HasSubstr("'speed' is not one of"));
  EXPECT_THAT(bad.err, HasSubstr("Usage: vt fly"));
}

// Quality against the reference images (every page resident): streaming from the coarsest level
// with a small budget loses quality; with every page resident from the start it is the reference
// up to the cache texture's coordinate rounding.
TEST_F(VtCommand, FlyMeasuresQualityAgainstEveryPageResident) {
  const auto texture = sparseTexture();
  const auto fly = [&](const std::vector<std::string>& extra, const std::string& out) {
    std::vector<std::string> args = {
        "fly", texture, "--size", "96x64", "--quality", "-o", (dir_ / out).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = vt(args);
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_THAT(result.out, HasSubstr("quality against every page resident: mean SSIM"));
    std::ifstream in(dir_ / out / "summary.json");
    return nlohmann::json::parse(in);
  };
  const auto starved = fly({"--budget", "1", "--initial-levels", "1", "--cache-frames", "3"}, "a");
  const auto full = fly({"--initial-levels", "4", "--cache-frames", "12"}, "b");
  EXPECT_LT(starved["min_ssim"].get<double>(), 0.99);
  EXPECT_GT(starved["mean_rmse"].get<double>(), 1.0);
  EXPECT_GT(full["min_ssim"].get<double>(), 0.9999);
  EXPECT_LT(full["mean_rmse"].get<double>(), 0.1);
  EXPECT_LE(full["mean_wssim"].get<double>(), 1.0);
  std::ifstream csv(dir_ / "a" / "frames.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_THAT(header, testing::EndsWith(",rmse,ssim,wssim"));
}

// The strategy beyond the thesis runs by its name in data/chapter4/beyond.json; the ceiling
// there, which looks at the next frame's view, is refused by vt fly with one line.
TEST_F(VtCommand, FlyRunsAStrategyOfAConfigurationsFileByName) {
  const auto texture = sparseTexture();
  const std::string configs = std::string(VT_TEST_SOURCE_DIR) + "/../data/chapter4/beyond.json";
  const auto frozen =
      vt({"fly", texture, "--size", "96x64", "--config", configs, "--config-name",
          "Frozen: WeightedPixel Gain + LookAhead + parents 5", "-o", (dir_ / "f").string()});
  ASSERT_EQ(frozen.exitCode, 0) << frozen.err;
  std::ifstream in(dir_ / "f" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["ancestors"], "gain");
  EXPECT_EQ(summary["heuristic"], "weightedpixel");
  EXPECT_EQ(summary["trilinear_parents"], true);
  const auto ceiling = vt({"fly", texture, "--size", "96x64", "--config", configs,
                           "--config-name", "Ceiling 5", "-o", (dir_ / "c").string()});
  EXPECT_EQ(ceiling.exitCode, 1);
  EXPECT_THAT(ceiling.err, HasSubstr("selection ceiling picks pages with the next frame's view, "
                                     "which only vt eval draws"));
  const auto nameless = vt({"fly", texture, "--config-name", "PixelSum 5"});
  EXPECT_EQ(nameless.exitCode, 2);
  EXPECT_THAT(nameless.err, HasSubstr("--config-name requires --config"));
}

TEST_F(VtCommand, BuildErrorsNameTheFile) {
  std::ofstream(dir_ / "layout.json") << R"({"images": [{"file": "gone.png", "x": 0, "y": 0}]})";
  const auto output = (dir_ / "out.vt").string();
  const auto missing = vt({"build", (dir_ / "layout.json").string(), "-o", output});
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_THAT(missing.err, MatchesRegex("vt: .*gone.png: image not found \\(named by .*layout.json "
                                        "images\\[0\\]\\)\n"));
  EXPECT_FALSE(std::filesystem::exists(output));
  const auto badFilter = vt({"build", "x.png", "-o", output, "--filter", "lanczos"});
  EXPECT_EQ(badFilter.exitCode, 2);
  EXPECT_THAT(badFilter.err, HasSubstr("Usage: vt build"));
}

TEST_F(VtCommand, RenderDrawsTheBoxRoomAndMeasuresAgainstAReference) {
  const auto texture = sparseTexture();
  const auto frame = (dir_ / "frame.png").string(), need = (dir_ / "need.png").string();
  const auto result = vt(
      {"render", texture, "--size", "96x64", "-o", frame, "--needbuffer", need, "--threads", "2"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(
      result.out,
      MatchesRegex("rendered .*frame.png: 96 x 64 in [0-9.]+ ms \\(oracle, profile exact\\), "
                   "6144 pixels covered, [0-9]+ distinct pages needed\n"));
  auto input = OIIO::ImageInput::open(need);
  ASSERT_TRUE(input);
  EXPECT_EQ(input->spec().width, 96);
  // The same frame against itself: no error.
  const auto again = vt({"render", texture, "--size", "96x64", "-o", (dir_ / "again.png").string(),
                         "--reference", frame});
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_THAT(again.out,
              HasSubstr("RMSE 0 (8-bit units), SSIM 1 (8 x 8), 1 (Gaussian 11 x 11), WSSIM 1,"));
  // A cache state of levels 0..1 only: coarser, so the error against the full frame is positive.
  const auto coarse =
      vt({"render", texture, "--size", "96x64", "-o", (dir_ / "coarse.png").string(),
          "--resident-levels", "2", "--reference", frame});
  ASSERT_EQ(coarse.exitCode, 0) << coarse.err;
  EXPECT_THAT(coarse.out, Not(HasSubstr("RMSE 0 ")));
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"render", texture, "--size", "0x5"},
        {"render", texture, "--camera", "1,2,nan:0,0,0"},
        {"render", texture, "--profile", "fast"}}) {
    const auto rejected = vt(bad);
    EXPECT_EQ(rejected.exitCode, 2) << rejected.err;
    EXPECT_THAT(rejected.err, HasSubstr("Usage: vt render"));
  }
}

}  // namespace
}  // namespace vt
