// vt-capture, the GPU-side program: it links none of the oracle's libraries, its captures judge
// bit for bit under the llvmpipe model on llvmpipe, and the probes it draws give `vt calibrate
// --probes` the same model file as `vt calibrate` drawing them itself; its flights streaming into
// the GL cache (every way: texel fetches, GL_LINEAR with a late needbuffer, BC1 blocks) give
// captures that judge bit for bit too. Damaged probe folders are refused with the file named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "eval/box_room_scene.h"
#include "gl/headless_context.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

class VtCapture : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("LP_NUM_THREADS", "2", 1);
    writeSyntheticTexture(dir_ / "t.vt",
                          {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  }
  test::CommandResult vt(const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir_.path());
  }
  test::CommandResult capture(const std::vector<std::string>& args) {
    return test::runCommand(VT_CAPTURE_EXECUTABLE, args, dir_.path());
  }
  bool llvmpipeWithFma() {
    const HeadlessContext context;
    return context.renderer().find("llvmpipe") != std::string::npos &&
           __builtin_cpu_supports("fma");
  }
  // `vt calibrate --record-probes requests -o here.json`, and the requests copied into kit/ as
  // the kit carries them (gpu-kit.sh leaves out results and sweeps' .delta files); with
  // sweeps.json where `sweeps`; then `vt-capture probes kit -o drawn`, its output in `printed`.
  void drawKitProbes(bool sweeps, std::string& printed) {
    const test::CommandResult here =
        vt({"calibrate", "--record-probes", (dir_ / "requests").string(), "-o",
            (dir_ / "here.json").string()});
    ASSERT_EQ(here.exitCode, 0) << here.err;
    std::filesystem::create_directory(dir_ / "kit");
    for (const auto& entry : std::filesystem::directory_iterator(dir_ / "requests")) {
      const std::string name = entry.path().filename().string();
      if ((name.starts_with("probe-") || (sweeps && name == "sweeps.json")) &&
          !name.ends_with(".result"))
        std::filesystem::copy_file(entry.path(), dir_ / "kit" / name);
    }
    const test::CommandResult drawn =
        capture({"probes", (dir_ / "kit").string(), "-o", (dir_ / "drawn").string()});
    ASSERT_EQ(drawn.exitCode, 0) << drawn.err;
    printed = drawn.out;
  }
  // `vt calibrate --probes drawn -o NAME`: the evidence by parameter, and "point" the point.
  std::map<std::string, nlohmann::json> fitDrawn(const char* name) {
    const test::CommandResult fitted =
        vt({"calibrate", "--probes", (dir_ / "drawn").string(), "-o", (dir_ / name).string()});
    EXPECT_EQ(fitted.exitCode, 0) << fitted.err;
    const nlohmann::json model = nlohmann::json::parse(test::slurp(dir_ / name));
    std::map<std::string, nlohmann::json> byName;
    for (const nlohmann::json& p : model["calibration"]["parameters"])
      byName[p["parameter"].get<std::string>()] = p;
    byName["point"] = model["calibration"]["point"];
    return byName;
  }
  test::ScratchDirectory dir_;
};

// ldd's libraries of vt-capture: the C library's own, libepoxy (which opens EGL and GL by name at
// run time) and xxhash; no C++ runtime (linked statically), image library, Embree, TBB or libzip.
TEST_F(VtCapture, LinksOnlyWhatDrawingNeeds) {
  // A sanitizer's runtime brings its own libraries (GCC links it as one, clang into the program).
  if (test::kAddressSanitizer || test::kThreadSanitizer)
    GTEST_SKIP() << "a sanitizer build: its runtime brings its own libraries";
  const test::CommandResult ldd =
      test::runCommand("/usr/bin/ldd", {VT_CAPTURE_EXECUTABLE}, dir_.path());
  ASSERT_EQ(ldd.exitCode, 0) << ldd.err;
  const std::vector<std::string> allowed = {"linux-vdso", "ld-linux",    "libc.so",
                                            "libm.so",    "libdl.so",    "libpthread.so",
                                            "librt.so",   "libepoxy.so", "libxxhash.so"};
  std::istringstream lines(ldd.out);
  int libraries = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    ++libraries;
    bool ok = false;
    for (const std::string& name : allowed) ok = ok || line.find(name) != std::string::npos;
    EXPECT_TRUE(ok) << "vt-capture needs " << line;
  }
  EXPECT_GE(libraries, 3);
}

TEST_F(VtCapture, ItsCapturesJudgeBitExactUnderLlvmpipe) {
  if (!llvmpipeWithFma()) GTEST_SKIP() << "not llvmpipe with FMA";
  const test::CommandResult drawn =
      capture({"scenes", (dir_ / "t.vt").string(), "--scenes", "room,coplanar,crossing", "--size",
               "160x100", "-o", (dir_ / "captures").string()});
  ASSERT_EQ(drawn.exitCode, 0) << drawn.err;
  for (const std::string model : {"llvmpipe", "gl45"}) {
    const test::CommandResult judged =
        vt({"crosscheck", "--captures", (dir_ / "captures").string(), "--model", model, "-o",
            (dir_ / ("report-" + model)).string()});
    EXPECT_EQ(judged.exitCode, 0) << model << "\n" << judged.out << judged.err;
    std::ifstream in(dir_ / ("report-" + model) / "summary.json");
    const auto summary = nlohmann::json::parse(in);
    EXPECT_EQ(summary["totals"]["pixels"], 6u * 16000u) << model;  // 3 scenes, 2 modes
    if (model == std::string("llvmpipe")) {
      EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
    }
  }
}

// The box room's storyboard flown with 2 pages a frame into a cache of 4 x 4 frames (pages are
// streamed and evicted throughout), a capture every 4th frame: each judges bit for bit under the
// llvmpipe model, and the cache the captures record changes along the flight.
TEST_F(VtCapture, FlightsStreamingIntoTheGlCacheJudgeBitExactUnderLlvmpipe) {
  if (!llvmpipeWithFma()) GTEST_SKIP() << "not llvmpipe with FMA";
  test::writeBoxRoomScene(dir_.path());
  writeSyntheticTexture(
      dir_ / "bc1.vt",
      {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4, .format = PixelFormat::kBc1},
       0.45});
  const std::vector<std::pair<std::string, std::vector<std::string>>> flights = {
      {"t.vt", {}},
      {"t.vt", {"--linear", "--async-readback", "--heuristic", "pixelsum*distance"}},
      {"bc1.vt", {}}};
  for (const auto& [texture, options] : flights) {
    SCOPED_TRACE(texture + (options.empty() ? "" : " " + options.front()));
    std::vector<std::string> args = {"flight",
                                     (dir_ / texture).string(),
                                     "--mesh",
                                     (dir_ / "room.obj").string(),
                                     "--path",
                                     (dir_ / "path.json").string(),
                                     "--size",
                                     "96x60",
                                     "--budget",
                                     "2",
                                     "--cache-frames",
                                     "4",
                                     "--every",
                                     "4",
                                     "-o",
                                     (dir_ / "flight").string()};
    args.insert(args.end(), options.begin(), options.end());
    std::filesystem::remove_all(dir_ / "flight");
    const test::CommandResult flown = capture(args);
    ASSERT_EQ(flown.exitCode, 0) << flown.err;
    EXPECT_THAT(flown.out, HasSubstr("flew 29 frames"));
    const auto record = nlohmann::json::parse(test::slurp(dir_ / "flight" / "flight.summary"));
    EXPECT_EQ(record["totals"]["captures"], 8);
    EXPECT_GT(record["totals"]["streamed"].get<int>(), 8);
    EXPECT_GT(record["totals"]["evicted"].get<int>(), 0);
    const auto first = nlohmann::json::parse(test::slurp(dir_ / "flight" / "frame0000.json"));
    const auto last = nlohmann::json::parse(test::slurp(dir_ / "flight" / "frame0028.json"));
    EXPECT_NE(first["cache"]["pages"], last["cache"]["pages"]);
    const test::CommandResult judged =
        vt({"crosscheck", "--captures", (dir_ / "flight").string(), "--model", "llvmpipe", "-o",
            (dir_ / "judged").string()});
    ASSERT_EQ(judged.exitCode, 0) << judged.out << judged.err;
    const auto summary = nlohmann::json::parse(test::slurp(dir_ / "judged" / "summary.json"));
    EXPECT_EQ(summary["totals"]["pixels"], 8u * 96u * 60u);
    EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  }
}

TEST_F(VtCapture, ProbesDrawnByItGiveTheModelCalibrateMeasures) {
  const test::CommandResult here = vt({"calibrate", "--record-probes", (dir_ / "requests").string(),
                                       "-o", (dir_ / "here.json").string()});
  ASSERT_EQ(here.exitCode, 0) << here.err;
  const test::CommandResult drawn =
      capture({"probes", (dir_ / "requests").string(), "-o", (dir_ / "drawn").string()});
  ASSERT_EQ(drawn.exitCode, 0) << drawn.err;
  const test::CommandResult fitted = vt({"calibrate", "--probes", (dir_ / "drawn").string(), "-o",
                                         (dir_ / "elsewhere.json").string()});
  ASSERT_EQ(fitted.exitCode, 0) << fitted.err;
  EXPECT_EQ(test::slurp(dir_ / "here.json"), test::slurp(dir_ / "elsewhere.json"));

  // A probe changed after it was drawn: not the draw this vt calibrate asks for.
  {
    std::fstream inputs(dir_ / "drawn" / "probe-0000.inputs.f32",
                        std::ios::in | std::ios::out | std::ios::binary);
    inputs.seekp(0);
    inputs.put('\x7f');
  }
  const test::CommandResult changed = vt(
      {"calibrate", "--probes", (dir_ / "drawn").string(), "-o", (dir_ / "changed.json").string()});
  EXPECT_EQ(changed.exitCode, 1);
  EXPECT_THAT(changed.err, HasSubstr("probe draw 0 is not the one this vt calibrate asks for"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "changed.json"));

  // A result cut short.
  std::filesystem::resize_file(dir_ / "requests" / "probe-0001.result", 100);
  std::filesystem::copy_file(dir_ / "requests" / "probe-0001.result",
                             dir_ / "drawn" / "probe-0001.result",
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(dir_ / "requests" / "probe-0000.inputs.f32",
                             dir_ / "drawn" / "probe-0000.inputs.f32",
                             std::filesystem::copy_options::overwrite_existing);
  const test::CommandResult cut =
      vt({"calibrate", "--probes", (dir_ / "drawn").string(), "-o", (dir_ / "cut.json").string()});
  EXPECT_EQ(cut.exitCode, 1);
  EXPECT_THAT(cut.err, HasSubstr("probe-0001.result"));
}

// The probe pack's sweeps: log2 of every float of [0.5, 2), sqrt of every float of [1, 4), the
// reciprocal of every float of [1, 2) and gl_FragDepth of every float of [0.5, 1) and of
// [2^-8, 2^-7) into Z24, drawn by vt-capture from the pixel index and fitted offline, pin
// llvmpipe's log2, sqrt, reciprocal and Z24 conversion over every input; one value changed after
// drawing unpins its family and is counted, and a NaN or a depth beyond 24 bits is refused naming
// the rule.
TEST_F(VtCapture, SweepsOfEveryFloatPinLlvmpipesFunctionsAndZ24) {
  if (!llvmpipeWithFma()) GTEST_SKIP() << "not llvmpipe with FMA";
  std::string printed;
  ASSERT_NO_FATAL_FAILURE(drawKitProbes(true, printed));
  EXPECT_THAT(printed, HasSubstr("and 5 sweeps of 58720256 inputs on llvmpipe"));
  auto parameters = fitDrawn("elsewhere.json");
  EXPECT_EQ(test::slurp(dir_ / "here.json"), test::slurp(dir_ / "elsewhere.json"));
  for (const char* function : {"log2", "sqrt"}) {
    SCOPED_TRACE(function);
    EXPECT_TRUE(parameters[function]["pinned"].get<bool>());
    EXPECT_EQ(parameters[function]["probes"].get<uint64_t>(), 65536u + (1u << 24));
    EXPECT_THAT(parameters[function]["probe"].get<std::string>(),
                HasSubstr("log2 of every float of [0.5, 2), sqrt of every float of [1, 4)"));
  }
  EXPECT_TRUE(parameters["reciprocal"]["pinned"].get<bool>());
  EXPECT_EQ(parameters["reciprocal"]["probes"].get<uint64_t>(), 1u << 23);
  EXPECT_EQ(parameters["reciprocal"]["finding"].get<std::string>(),
            "IEEE division, correctly rounded, bit for bit");
  EXPECT_TRUE(parameters["z24"]["pinned"].get<bool>());
  EXPECT_GT(parameters["z24"]["probes"].get<uint64_t>(), 1u << 24);
  // In [0.5, 1) the float product is whole (rounding and truncation agree there); in the lower
  // binade they part, and the exact product parts from llvmpipe's float product at the ties.
  EXPECT_THAT(parameters["z24"]["finding"].get<std::string>(),
              HasSubstr("nearest_even 0 of 16861951 differ, truncated 4172536 of 16861951"));
  EXPECT_THAT(parameters["z24"]["finding"].get<std::string>(),
              HasSubstr("the exact product z (2^24 - 1) rounded to nearest: 32768 of 16777216"));

  // A sweep's file decoded, changed at input `at` and coded again (capture/sweep_files.h).
  const auto change = [&](const char* sweep, size_t at,
                          const std::function<uint32_t(uint32_t)>& into) {
    const std::filesystem::path file = dir_ / "drawn" / (std::string("sweep-") + sweep + ".delta");
    std::vector<uint32_t> values(std::filesystem::file_size(file) / 4);
    std::ifstream(file, std::ios::binary)
        .read(reinterpret_cast<char*>(values.data()),
              static_cast<std::streamsize>(values.size() * 4));
    for (size_t i = 1; i < values.size(); ++i) values[i] += values[i - 1];
    values[at] = into(values[at]);
    for (size_t i = values.size() - 1; i > 0; --i) values[i] -= values[i - 1];
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(values.data()),
               static_cast<std::streamsize>(values.size() * 4));
  };
  // log2 of input 5,000,000 (in [0.5, 1)) one ulp off: log2 is no longer pinned, by one value;
  // the reciprocal of input 123 likewise; a stored depth one step off unpins Z24.
  change("log2", 5000000, [](uint32_t bits) { return bits + 1; });
  change("reciprocal", 123, [](uint32_t bits) { return bits - 1; });
  change("frag_depth_low", 7, [](uint32_t stored) { return stored + 1; });
  parameters = fitDrawn("changed.json");
  EXPECT_FALSE(parameters["log2"]["pinned"].get<bool>());
  EXPECT_EQ(parameters["log2"]["mismatches"].get<uint64_t>(), 1u);
  EXPECT_THAT(parameters["log2"]["finding"].get<std::string>(),
              HasSubstr("polynomial_fused 1 of 16842752 differ"));
  EXPECT_FALSE(parameters["reciprocal"]["pinned"].get<bool>());
  EXPECT_THAT(parameters["reciprocal"]["finding"].get<std::string>(),
              HasSubstr("1 of 8388608 differ from IEEE division, largest 1."));
  EXPECT_FALSE(parameters["z24"]["pinned"].get<bool>());
  EXPECT_EQ(parameters["z24"]["mismatches"].get<uint64_t>(), 1u);

  // A stored depth beyond 24 bits.
  change("frag_depth_low", 7, [](uint32_t) { return 1u << 24; });
  const test::CommandResult deep =
      vt({"calibrate", "--probes", (dir_ / "drawn").string(), "-o", (dir_ / "deep.json").string()});
  EXPECT_EQ(deep.exitCode, 1);
  EXPECT_THAT(deep.err, HasSubstr("the depth sweep frag_depth_low returned 16777216 at input 7, "
                                  "which is no 24-bit depth value"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "deep.json"));

  // NaN in log2's place.
  change("log2", 5000000,
         [](uint32_t) { return std::bit_cast<uint32_t>(std::numeric_limits<float>::quiet_NaN()); });
  const test::CommandResult refused =
      vt({"calibrate", "--probes", (dir_ / "drawn").string(), "-o", (dir_ / "nan.json").string()});
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_THAT(refused.err, HasSubstr("breaks a rule (GL 4.5 core, section 2.3.4"));
  EXPECT_THAT(refused.err, HasSubstr("the sweep of log2(x) over every float from 0.5"));
  EXPECT_THAT(refused.err, HasSubstr("returned NaN at input 5000000"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "nan.json"));
}

// The pack's groups, the plane group (calibrate/plane_probes.h), GL_LINEAR at the cache's sizes
// (calibrate/filter_fit.h) and the noperspective group (calibrate/noperspective_fit.h): drawn by
// vt-capture from the kit's requests and fitted offline they pin llvmpipe's plane evaluation, Z24
// conversion and filter with them, show that llvmpipe's values move when the triangle does, and
// reproduce its noperspective coordinates by the members its perspective ones chose; a folder
// drawn before a group (its probes.json ends where the group begins, as the H100's) fits the same
// point without it; a folder that ends inside a group is refused.
TEST_F(VtCapture, TheGroupsPinLlvmpipeAndAFolderWithoutThemFitsAsBefore) {
  if (!llvmpipeWithFma()) GTEST_SKIP() << "not llvmpipe with FMA";
  std::string printed;
  ASSERT_NO_FATAL_FAILURE(drawKitProbes(false, printed));
  EXPECT_THAT(printed, HasSubstr("drew 44 probe draws"));
  auto withGroup = fitDrawn("with.json");
  for (const char* family :
       {"plane_evaluation", "plane_setup", "attributes", "depth", "z24", "filter"}) {
    SCOPED_TRACE(family);
    EXPECT_TRUE(withGroup[family]["pinned"].get<bool>());
  }
  EXPECT_THAT(withGroup["plane_setup"]["probe"].get<std::string>(),
              HasSubstr("shifted by 1 to 512 pixels"));
  EXPECT_THAT(withGroup["plane_evaluation"]["finding"].get<std::string>(),
              HasSubstr("change from a shift of 1: the planes are evaluated from a fixed origin"));
  EXPECT_THAT(withGroup["filter"]["probe"].get<std::string>(),
              HasSubstr("at the cache's sizes, 16384 x 2, 2 x 16384 and 4080 x 4"));
  EXPECT_THAT(withGroup["filter"]["probe"].get<std::string>(),
              HasSubstr("BC1 and BC3 textures of 4096 x 8"));
  EXPECT_THAT(withGroup["filter"]["finding"].get<std::string>(),
              HasSubstr("fixed_point_8 0 of 90112 differ"));
  EXPECT_EQ(withGroup["z24"]["probe"].get<std::string>(),
            "4,096 squares of constant depth and 120 random triangles drawn into a Z24 depth "
            "buffer");
  EXPECT_THAT(withGroup["z24"]["finding"].get<std::string>(),
              HasSubstr("nearest_even 0 of 84735 differ, truncated 10999 of 84735 differ"));
  // Vertices on the 1/256 grid: snapped and unsnapped positions coincide on llvmpipe's grid.
  EXPECT_TRUE(withGroup["noperspective_planes"]["pinned"].get<bool>());
  EXPECT_EQ(withGroup["noperspective_planes"]["chosen"], "first_vertex/unsnapped/fused");
  EXPECT_THAT(withGroup["noperspective_planes"]["finding"].get<std::string>(),
              HasSubstr("first_vertex/snapped/fused 0 of 131072 differ, "
                        "first_vertex/snapped/unfused 63778 of 131072 differ"));

  // The first 22 draws alone, as a folder drawn before the group.
  const std::filesystem::path description = dir_ / "drawn" / "probes.json";
  nlohmann::json probes = nlohmann::json::parse(test::slurp(description));
  ASSERT_EQ(probes["count"], 44);
  // Without the noperspective group (the last two draws).
  probes["count"] = 42;
  std::ofstream(description, std::ios::trunc) << probes.dump();
  const auto withoutNoperspective = fitDrawn("no-noperspective.json");
  EXPECT_EQ(withoutNoperspective.at("point"), withGroup["point"]);
  EXPECT_FALSE(withoutNoperspective.contains("noperspective_planes"));
  // Without the filter group (the five draws before).
  probes["count"] = 37;
  std::ofstream(description, std::ios::trunc) << probes.dump();
  const auto withoutFilterGroup = fitDrawn("plane-group-only.json");
  EXPECT_EQ(withoutFilterGroup.at("point"), withGroup["point"]);
  EXPECT_THAT(withoutFilterGroup.at("filter")["probe"].get<std::string>(), Not(HasSubstr("cache")));
  EXPECT_EQ(withoutFilterGroup.at("z24")["probe"], withGroup["z24"]["probe"]);

  probes["count"] = 22;
  std::ofstream(description, std::ios::trunc) << probes.dump();
  auto without = fitDrawn("without.json");
  EXPECT_EQ(without["point"], withGroup["point"]);
  EXPECT_EQ(without["z24"]["probe"].get<std::string>(),
            "120 random triangles drawn into a Z24 depth buffer");
  EXPECT_THAT(without["plane_evaluation"]["finding"].get<std::string>(), Not(HasSubstr("shifted")));

  probes["count"] = 30;
  std::ofstream(description, std::ios::trunc) << probes.dump();
  const test::CommandResult cut =
      vt({"calibrate", "--probes", (dir_ / "drawn").string(), "-o", (dir_ / "cut.json").string()});
  EXPECT_EQ(cut.exitCode, 1);
  EXPECT_THAT(cut.err, HasSubstr("holds 30 probe draws, which ends inside a group of 15 from "
                                 "draw 22 (a folder cut short?)"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "cut.json"));
}

TEST_F(VtCapture, BadArgumentsAndInputs) {
  const test::CommandResult none = capture({});
  EXPECT_EQ(none.exitCode, 2);
  const test::CommandResult size =
      capture({"scenes", (dir_ / "t.vt").string(), "--size", "0x5", "-o", (dir_ / "o").string()});
  EXPECT_EQ(size.exitCode, 2);
  EXPECT_THAT(size.err, HasSubstr("Usage"));
  std::filesystem::create_directories(dir_ / "empty");
  const test::CommandResult empty =
      capture({"probes", (dir_ / "empty").string(), "-o", (dir_ / "out").string()});
  EXPECT_EQ(empty.exitCode, 1);
  EXPECT_THAT(empty.err, HasSubstr("holds no probe request"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
  // A texture as long as a cache's side is drawn (filter_fit.h), but not 2^23 texels.
  std::filesystem::create_directories(dir_ / "large");
  std::ofstream(dir_ / "large" / "probe-0000.json")
      << R"({"format": "vt-probe", "version": 1, "kind": "shader", "body": "", "width": 1,
            "input_count": 1, "linear": true, "clipped": false, "texels": "t",
            "texture_size": [16384, 512]})";
  std::ofstream(dir_ / "large" / "probe-0000.inputs.f32", std::ios::binary)
      << std::string(16, '\0');
  const test::CommandResult large =
      capture({"probes", (dir_ / "large").string(), "-o", (dir_ / "out").string()});
  EXPECT_EQ(large.exitCode, 1);
  EXPECT_THAT(large.err, HasSubstr((dir_ / "large" / "probe-0000.json").string() +
                                   ": texture_size 16384 x 512 is more than 4,194,304 texels"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
  const test::CommandResult scene = capture(
      {"scenes", (dir_ / "t.vt").string(), "--scenes", "nowhere", "-o", (dir_ / "o").string()});
  EXPECT_EQ(scene.exitCode, 1);
  EXPECT_THAT(scene.err, HasSubstr("nowhere"));
  test::writeBoxRoomScene(dir_.path());
  const std::vector<std::string> flight = {
      "flight", (dir_ / "t.vt").string(),      "--mesh", (dir_ / "room.obj").string(),
      "--path", (dir_ / "path.json").string(), "-o",     (dir_ / "f").string()};
  std::vector<std::string> args = flight;
  args.insert(args.end(), {"--heuristic", "speed"});
  const test::CommandResult heuristic = capture(args);
  EXPECT_EQ(heuristic.exitCode, 2);
  EXPECT_THAT(heuristic.err, HasSubstr("'speed' is not one of"));
  EXPECT_THAT(heuristic.err, HasSubstr("Usage"));
  args = flight;
  args.insert(args.end(), {"--cache-frames", "1000"});  // 1000 x 36 texels: over 16384
  const test::CommandResult cache = capture(args);
  EXPECT_EQ(cache.exitCode, 1);
  EXPECT_THAT(cache.err, HasSubstr((dir_ / "t.vt").string() + ": a cache of 1000 frames"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "f"));
}

}  // namespace
}  // namespace vt
