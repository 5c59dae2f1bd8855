// Hostile input through the command line (issue 20): an output that is an input or a device, a
// FIFO, a device or a folder where a file belongs, a name with a NUL, a golden set missing a
// field, and failures that must leave no partial output. Each ends in one line naming the file and
// exit code 1, before any output is touched.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "common/image_file.h"
#include "eval/box_room_scene.h"
#include "format/virtual_texture_writer.h"
#include "scene/quake3_fixtures.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;

class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    writeSyntheticTexture(dir_ / "t.vt",
                          {{.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4}, 0.5});
    writeImage8(dir_ / "image.png", 8, 8, 3, std::vector<std::byte>(8 * 8 * 3, std::byte{9}));
    test::writeBoxRoomScene(dir_.path());
  }
  test::CommandResult vt(const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir_.path());
  }
  // `vt` run by the shell after `limits` (ulimit commands). SIGXFSZ is ignored, so a write beyond
  // `ulimit -f` fails (EFBIG) as on a full disk instead of killing the process.
  test::CommandResult vtUnder(const std::string& limits, const std::vector<std::string>& args) {
    std::vector<std::string> shell = {"-c", "trap '' XFSZ; " + limits + "; exec \"$0\" \"$@\"",
                                      VT_EXECUTABLE};
    shell.insert(shell.end(), args.begin(), args.end());
    return test::runCommand("/bin/sh", shell, dir_.path());
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // No entry of the scratch folder has `name` in its name (the output, or a temporary beside it).
  void expectNothingNamed(const std::string& name) const {
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path()))
      EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(name))) << "left behind";
  }
  std::string fifo(const std::string& name) const {
    EXPECT_EQ(::mkfifo(path(name).c_str(), 0600), 0);
    return path(name);
  }
  // One line, exit code 1, naming `file` and the problem.
  static void expectOneLine(const test::CommandResult& result, const std::string& file,
                            const std::string& problem) {
    EXPECT_EQ(result.exitCode, 1) << result.err;
    EXPECT_THAT(result.err, HasSubstr(file + ": ")) << result.err;
    EXPECT_THAT(result.err, HasSubstr(problem)) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
  test::ScratchDirectory dir_;
};

// Class 2: an output that is one of the inputs, by any name, or a device or FIFO, is refused
// before any work, and the input is left as it was.
TEST_F(HostileInput, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  const auto image = test::readBytes(path("image.png"));
  expectOneLine(vt({"build", path("image.png"), "-o", path("image.png"), "-q"}), path("image.png"),
                "is the input " + path("image.png"));
  // Another name for the same file.
  std::filesystem::create_hard_link(path("image.png"), path("alias.png"));
  expectOneLine(vt({"build", path("image.png"), "-o", path("alias.png"), "-q"}), path("alias.png"),
                "is the input");
  EXPECT_EQ(test::readBytes(path("image.png")), image);

  // The image a layout names.
  std::ofstream(path("layout.json")) << R"({"page_size": 8, "border": 1,
    "images": [{"file": "image.png", "x": 0, "y": 0}]})";
  expectOneLine(vt({"build", path("layout.json"), "-o", path("image.png"), "-q"}),
                path("image.png"), "is the input");
  EXPECT_EQ(test::readBytes(path("image.png")), image);

  // The reference image of `vt render`.
  expectOneLine(vt({"render", path("t.vt"), "--size", "16x16", "-o", path("image.png"),
                    "--reference", path("image.png")}),
                path("image.png"), "is the input");
  EXPECT_EQ(test::readBytes(path("image.png")), image);
}

TEST_F(HostileInput, AnOutputThatIsNotARegularFileOrFolderIsRefused) {
  const std::string pipe = fifo("pipe");
  expectOneLine(vt({"build", path("image.png"), "-o", pipe, "-q"}), pipe,
                "is a FIFO, not a regular file");
  struct stat info {};
  ASSERT_EQ(::stat(pipe.c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));  // not renamed over
  expectOneLine(vt({"export-level", path("t.vt"), "--level", "0", "-o", pipe}), pipe, "is a FIFO");
  expectOneLine(vt({"build", path("image.png"), "-o", "/dev/full", "-q"}), "/dev/full",
                "is a character device");
  expectOneLine(vt({"fly", path("t.vt"), "--size", "16x16", "-o", pipe}), pipe,
                "is a FIFO, not a folder");
  // A folder output holding an input would remove it when the folder is replaced.
  std::filesystem::create_directories(dir_ / "out");
  std::filesystem::copy_file(path("path.json"), dir_ / "out" / "path.json");
  expectOneLine(vt({"fly", path("t.vt"), "--size", "16x16", "--path", path("out/path.json"), "-o",
                    path("out")}),
                path("out"), "holds the input");
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out" / "path.json"));
}

// Classes 4 and 6: a FIFO, a device or a folder given where an input file belongs is refused with
// one line naming it, never waited on or read without end.
TEST_F(HostileInput, SpecialFilesAndFoldersAsInputsGiveOneLine) {
  const std::string pipe = fifo("pipe");
  std::filesystem::create_directories(dir_ / "folder");
  const std::string folder = path("folder");
  const std::vector<std::string> render = {"render", path("t.vt"), "--size",
                                           "16x16",  "-o",         path("r.png")};
  const auto with = [&](std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  expectOneLine(vt(with(render, {"--mesh", pipe})), pipe, "it is a FIFO, not a regular file");
  expectOneLine(vt(with(render, {"--mesh", folder})), folder, "cannot read mesh: it is a folder");
  expectOneLine(vt({"info", pipe}), pipe, "not a regular file");
  expectOneLine(vt({"build", pipe, "-o", path("x.vt"), "-q"}), pipe, "not a regular file");
  std::filesystem::create_directories(dir_ / "layout.json");
  expectOneLine(vt({"build", path("layout.json"), "-o", path("x.vt"), "-q"}), path("layout.json"),
                "cannot read layout file: it is a folder");
  const std::vector<std::string> fly = {"fly", path("t.vt"), "--size", "16x16", "-o", path("f")};
  expectOneLine(vt(with(fly, {"--path", pipe})), pipe, "it is a FIFO, not a regular file");
  expectOneLine(vt(with(fly, {"--path", folder})), folder,
                "cannot read camera path: it is a folder");
  expectOneLine(vt(with(fly, {"--config", pipe})), pipe, "it is a FIFO, not a regular file");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "f"));

  // /dev/zero as a layout's image, and an image name cut by a NUL.
  std::ofstream(path("zero.json")) << R"({"page_size": 8, "border": 1,
    "images": [{"file": "/dev/zero", "x": 0, "y": 0}]})";
  expectOneLine(vt({"build", path("zero.json"), "-o", path("x.vt"), "-q"}), "/dev/zero",
                "it is a character device, not a regular file");
  std::ofstream(path("nul.json")) << R"({"page_size": 8, "border": 1,
    "images": [{"file": "image.png\u0000.txt", "x": 0, "y": 0}]})";
  const auto nul = vt({"build", path("nul.json"), "-o", path("x.vt"), "-q"});
  expectOneLine(nul, path("image.png"), "holds a NUL character");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.vt"));

  // An OBJ scene's material library.
  std::ofstream(path("scene.obj"))
      << "mtllib pipe\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n";
  expectOneLine(vt({"retexture", path("scene.obj"), "-o", path("rt"), "--no-coherence"}), pipe,
                "it is a FIFO, not a regular file");
}

TEST_F(HostileInput, AGoldenSetMissingAFieldNamesTheFieldInOneLine) {
  const auto generated =
      vt({"golden", "generate", path("t.vt"), "--mesh", path("room.obj"), "--path",
          path("path.json"), "--size", "16x16", "--every", "9", "-o", path("golden")});
  ASSERT_EQ(generated.exitCode, 0) << generated.err;
  const std::filesystem::path manifest = dir_ / "golden" / "golden.json";
  for (const char* field : {"mesh_checksum", "texture_identity"}) {
    nlohmann::json golden = nlohmann::json::parse(test::slurp(manifest));
    golden.erase(field);
    std::ofstream(manifest) << golden.dump();
    const auto result = vt({"golden", "check", path("golden"), "--texture", path("t.vt"), "--mesh",
                            path("room.obj"), "--path", path("path.json"), "-o", path("check")});
    expectOneLine(result, manifest.string(),
                  "not a golden set: key '" + std::string(field) + "' not found");
    EXPECT_THAT(result.err, Not(HasSubstr("json.exception")));
  }
}

// Class 7: a flight that fails, early or late, leaves no output folder and no frames.
TEST_F(HostileInput, AFailedFlightLeavesNoOutput) {
  const auto bytes = test::readBytes(path("t.vt"));
  uint64_t dataOffset = 0;  // file_header.h: u64 data_offset at byte 80, pages in rising p_abs
  for (int i = 7; i >= 0; --i)
    dataOffset = dataOffset << 8 | std::to_integer<uint64_t>(bytes[80 + i]);
  const size_t pageBytes = 20 * 20 * 4;
  const auto corrupt = [&](const std::string& name, size_t from) {
    auto damaged = bytes;
    for (size_t i = from; i < damaged.size(); i += 7) damaged[i] ^= std::byte{0x55};
    test::writeBytes(path(name), damaged);
    return path(name);
  };
  const auto expectNothingLeft = [&](const test::CommandResult& result, const std::string& out) {
    EXPECT_EQ(result.exitCode, 1) << result.err;
    EXPECT_THAT(result.err, HasSubstr("checksum mismatch"));
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path()))
      EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(out))) << "left behind";
  };
  // Early: the root page, loaded before the first frame.
  expectNothingLeft(vt({"fly", corrupt("root.vt", dataOffset), "--size", "32x32", "--capture",
                        path("early-captures"), "-o", path("early")}),
                    "early");
  // Late: the pages of the finest level (beyond the 21 of levels 0 to 2), streamed after frames
  // were drawn, captured and written.
  expectNothingLeft(
      vt({"fly", corrupt("finest.vt", dataOffset + 21 * pageBytes), "--size", "32x32",
          "--images-every", "1", "--capture", path("late-captures"), "-o", path("late")}),
      "late");
  // Each folder takes its place whole, so one may not lie in the other (a bad argument).
  const auto nested = vt(
      {"fly", path("t.vt"), "--size", "16x16", "--capture", path("n/captures"), "-o", path("n")});
  EXPECT_EQ(nested.exitCode, 2) << nested.err;
  EXPECT_THAT(nested.err, HasSubstr("may not lie in one another"));
}

// Class 7: `vt crosscheck -o` and `vt demo` that fail part way (here on a disk that fills up:
// files of at most 2 KiB) leave no output folder and nothing beside it.
TEST_F(HostileInput, ACrosscheckOrDemoThatFailsLeavesNoOutput) {
  const auto flown = vt({"fly", path("t.vt"), "--size", "32x32", "--capture", path("captures"),
                         "--capture-every", "10", "-o", path("f")});
  ASSERT_EQ(flown.exitCode, 0) << flown.err;
  const auto checked =
      vtUnder("ulimit -f 4", {"crosscheck", "--captures", path("captures"), "-o", path("check")});
  EXPECT_EQ(checked.exitCode, 1) << checked.err;
  EXPECT_THAT(checked.err, HasSubstr("File too large"));
  expectNothingNamed("check");
  const auto demo = vtUnder("ulimit -f 4", {"demo", "-o", path("demo")});
  EXPECT_EQ(demo.exitCode, 1) << demo.err;
  EXPECT_THAT(demo.err, HasSubstr("File too large"));
  expectNothingNamed("demo");
}

// Class 7: a map whose entity lump is malformed, read after its images were extracted, leaves no
// output folder (and so no OUT/images/).
TEST_F(HostileInput, ARetextureThatFailsLeavesNoOutput) {
  test::BspBuilder map;
  map.entities = "{\n\"classname\" \"worldspawn\"\n";  // never closed
  map.shaders = {{"textures/base/wall", 0, 1}};
  map.vertices = {{{0, 0, 0}, {0, 0}, {0, 0, 1}},
                  {{0, 64, 0}, {0, 1}, {0, 0, 1}},
                  {{64, 64, 0}, {1, 1}, {0, 0, 1}}};
  map.indices = {0, 1, 2};
  BspSurface surface;
  surface.shader = 0;
  surface.type = static_cast<int32_t>(BspSurfaceType::kPolygon);
  surface.firstVertex = 0, surface.vertexCount = 3, surface.firstIndex = 0, surface.indexCount = 3;
  map.surfaces = {surface};
  const std::vector<uint8_t> bsp = map.build();
  std::ifstream png(path("image.png"), std::ios::binary);
  const std::string image((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>());
  std::filesystem::create_directories(dir_ / "baseoa");
  test::writeZip(
      dir_ / "baseoa" / "pak0.pk3",
      {{"maps/bad.bsp", std::string(bsp.begin(), bsp.end())}, {"textures/base/wall.jpg", image}});
  const auto result =
      vt({"retexture", "bad", "--packages", path("baseoa"), "-o", path("out"), "--no-coherence"});
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("pak0.pk3:maps/bad.bsp: entities"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
}

// Class 3: a valid 149-byte texture (page size 1, 16 levels, only the root stored) whose dense page
// tables would need 24 GB is refused before they are allocated, with the bytes they would need.
TEST_F(HostileInput, PageTablesForEveryPageOfEveryLevelAreRefusedUpFront) {
  TextureDescription d;
  d.pageSize = 1, d.border = 0, d.levelCount = 16, d.channels = 4;
  VirtualTextureWriter writer(dir_ / "deep.vt", d, {0});
  writer.writePage(PageId{}, std::vector<std::byte>(4, std::byte{200}), 0.0f);
  writer.commit();
  const std::string limit =
      "building the page tables of 16 levels (an entry for each of the 1431655765 pages, stored or "
      "not) "
      "asks for 24338148005 bytes, the limit is 2281701376 bytes";
  expectOneLine(vt({"render", path("deep.vt"), "--size", "16x16", "-o", path("r.png")}),
                path("deep.vt"), limit);
  expectOneLine(vt({"fly", path("deep.vt"), "--size", "16x16", "-o", path("f")}), path("deep.vt"),
                limit);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "f"));
}

// Class 3: `vt eval` flies its configurations in lockstep, each cache held at once; a file of 100
// configurations with the largest cache (a 4 kB file) is refused before the first frame, with the
// bytes they would hold: 100 x (256^2 frames of 20^2 RGBA8 texels + a 320 x 200 colour buffer).
TEST_F(HostileInput, AnEvaluationHoldingTooManyCachesIsRefusedUpFront) {
  {
    std::ofstream configs(path("many.json"));
    configs << R"({"configurations": [)";
    for (int c = 0; c < 100; ++c)
      configs << (c ? "," : "") << R"({"name": "c)" << c << R"(", "cache_frames": 256})";
    configs << "]}";
  }
  const auto result = vt({"eval", path("t.vt"), "--configs", path("many.json"), "--size",
                          "320x200", "-o", path("out")});
  expectOneLine(result, path("many.json"),
                "flying 100 configurations in lockstep (each cache and frame held at once) asks "
                "for 10511360000 bytes, the limit is 8589934592 bytes");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
  // A camera path missing a field names it without nlohmann's "[json.exception...]".
  std::ofstream(path("nopitch.json")) << R"({"keyframes": [{"frame": 0, "position": [0, 0, 0],
    "yaw": 0}]})";
  expectOneLine(vt({"fly", path("t.vt"), "--path", path("nopitch.json"), "-o", path("f")}),
                path("nopitch.json"), "not a camera path: key 'pitch' not found");
}

// Class 5: a path of a million frames (a 150-byte file) is refused before the first frame with
// the pixels it would draw; `vt eval` counts every configuration's run over the path.
TEST_F(HostileInput, APathDrawingTooManyPixelsIsRefusedUpFront) {
  const auto pathOf = [&](const std::string& name, int frames) {
    std::ofstream(path(name)) << R"({"keyframes": [
      {"frame": 0, "position": [6, 1.6, 4.5], "yaw": 0, "pitch": 0},
      {"frame": )" << frames - 1
                              << R"(, "position": [6, 1.6, 4.5], "yaw": 90, "pitch": 0}]})";
    return path(name);
  };
  expectOneLine(vt({"fly", path("t.vt"), "--path", pathOf("long.json", 1'000'000), "--size",
                    "320x200", "-o", path("out")}),
                path("long.json"),
                "drawing its 1000000 frames at 320 x 200 1 time asks for 64000000000 pixels, the "
                "limit is 34359738368 pixels");
  // A tiny screen does not make a frame free: each counts as at least kFrameFixedPixels.
  // (10^6 frames of 16 x 16, ten times over, would pass as 2.6 * 10^9 pixels: hours.)
  expectOneLine(vt({"eval", path("t.vt"), "--path", pathOf("tiny.json", 1'000'000), "--size",
                    "16x16", "--budget", "1,2,3,4,5,6,7,8,9", "-o", path("out")}),
                path("tiny.json"),
                "drawing its 1000000 frames at 16 x 16 10 times (a frame counts as at least 4096 "
                "pixels) asks for 40960000000 pixels, the limit is 34359738368 pixels");
  // 33,000 frames keep 8.4 GB of reference images, within that limit; 18 runs draw too much.
  expectOneLine(
      vt({"eval", path("t.vt"), "--path", pathOf("eval.json", 33'000), "--size", "320x200",
          "--budget", "1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17", "-o", path("out")}),
      path("eval.json"),
      "drawing its 33000 frames at 320 x 200 18 times asks for 38016000000 pixels, the "
      "limit is 34359738368 pixels");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
}

// Class 3: an image whose 18-byte header claims 65535^2 texels, on a face that spans it once, is
// measured by texel rows: `vt retexture` stays within 3 GB of address space (it needed a byte
// per claimed texel, 4.3 GB, and failed with std::bad_alloc).
// The header claims 65535 x 65535 texels over no pixel: the image is believed only as far as it
// decodes, so the quad gets the checker (it used to get a texture area of 131072^2 texels).
TEST_F(HostileInput, AnImageHeaderClaimingBillionsOfTexelsIsBelievedOnlyAsFarAsItDecodes) {
  std::vector<std::byte> tga(18, std::byte{0});  // uncompressed true colour, 24 bits, no data
  tga[2] = std::byte{2};
  for (const size_t at : {12u, 13u, 14u, 15u}) tga[at] = std::byte{0xff};
  tga[16] = std::byte{24};
  test::writeBytes(path("huge.tga"), tga);
  std::ofstream(path("huge.mtl")) << "newmtl m\nmap_Kd huge.tga\n";
  std::ofstream(path("huge.obj")) << "mtllib huge.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\n"
                                     "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  // AddressSanitizer reserves terabytes of address space for its shadow memory, so under it the
  // address-space limit is left out (the run still must succeed and measure the quad).
  const auto result = vtUnder(test::kAddressSanitizer ? "true" : "ulimit -v 3000000",
                              {"retexture", path("huge.obj"), "-o", path("out"), "--no-coherence"});
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out + result.err, HasSubstr("huge.tga is not a readable image"));
  EXPECT_THAT(result.out, HasSubstr("charts    side 128,"));
}

}  // namespace
}  // namespace vt
