// Sharding (`--shard I/N`, common/shard.h) and `vt merge`: the split is a partition that depends on
// the items' order alone, and the merged folder of N shards holds the bytes one run writes, for
// `vt crosscheck --captures`, `vt golden check` and `vt eval`, but for what the runs measured
// (times). Shards of different jobs, missing or repeated shards and tampered records are refused
// naming the shard's file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "common/shard.h"
#include "eval/box_room_scene.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(Shard, ParsesIOfNAndRefusesAnythingElse) {
  EXPECT_EQ(parseShard("2/8"), (Shard{2, 8}));
  EXPECT_EQ(parseShard("1/1"), (Shard{1, 1}));
  EXPECT_EQ(parseShard("100000/100000"), (Shard{100000, 100000}));
  for (const char* bad : {"", "1", "/", "0/3", "4/3", "1/0", "1/100001", "-1/3", "1/3/", " 1/3",
                          "1/3 ", "a/3", "1/b", "1.0/3", "+1/3", "99999999999/3"})
    EXPECT_THROW(parseShard(bad), std::invalid_argument) << bad;
}

TEST(Shard, TurnsAndBlocksEachPartitionTheItems) {
  for (const uint32_t count : {1u, 2u, 3u, 7u, 16u})
    for (const size_t items : {size_t{0}, size_t{1}, size_t{5}, size_t{16}, size_t{101}}) {
      std::vector<int> turns(items, 0), blocks(items, 0);
      size_t previousEnd = 0;
      for (uint32_t i = 1; i <= count; ++i) {
        const Shard shard{i, count};
        for (size_t k = 0; k < items; ++k) turns[k] += shard.holdsInTurn(k);
        const auto [first, end] = shard.block(items);
        EXPECT_EQ(first, previousEnd);  // contiguous, in order
        EXPECT_LE(end - first, (items + count - 1) / count);
        EXPECT_GE(end - first, items / count);
        for (size_t k = first; k < end; ++k) ++blocks[k];
        previousEnd = end;
      }
      EXPECT_EQ(previousEnd, items);
      for (size_t k = 0; k < items; ++k) {
        EXPECT_EQ(turns[k], 1) << count << " shards, item " << k;
        EXPECT_EQ(blocks[k], 1) << count << " shards, item " << k;
      }
    }
  // In turn: item k belongs to shard k mod N + 1, whatever the number of items.
  EXPECT_TRUE((Shard{3, 4}.holdsInTurn(6)));
  EXPECT_TRUE((Shard{1, 4}.holdsInTurn(8)));
}

// The files of a folder by name, each through `normalize(name, bytes)`.
using Normalize = std::function<std::string(const std::string&, std::string)>;
std::map<std::string, std::string> folderFiles(const std::filesystem::path& folder,
                                               const Normalize& normalize) {
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    files[name] = normalize(name, test::slurp(entry.path()));
  }
  return files;
}

void expectSameFolders(const std::filesystem::path& one, const std::filesystem::path& merged,
                       const Normalize& normalize) {
  const auto a = folderFiles(one, normalize), b = folderFiles(merged, normalize);
  std::set<std::string> namesA, namesB;
  for (const auto& [name, bytes] : a) namesA.insert(name);
  for (const auto& [name, bytes] : b) namesB.insert(name);
  ASSERT_EQ(namesA, namesB);
  for (const auto& [name, bytes] : a) EXPECT_TRUE(bytes == b.at(name)) << name << " differs";
}

// The text with every ` NAME="..."` attribute's value removed (std::regex is left out: GCC 12
// warns falsely in it under the sanitizers' -O1).
std::string withoutAttribute(std::string text, const std::string& name) {
  const std::string key = " " + name + "=\"";
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
    const size_t end = text.find('"', at + key.size());
    if (end == std::string::npos) break;
    text.erase(at, end + 1 - at);
  }
  return text;
}

std::string junitWithoutTimes(const std::string& name, std::string bytes) {
  return name == "junit.xml" ? withoutAttribute(bytes, "time") : bytes;
}

struct ShardFixture {
  test::ScratchDirectory dir;
  test::CommandResult vt(const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir.path());
  }
  // `command` run once into one/ and as `count` shards, merged (given in reverse order) into
  // merged/; each must exit with `exitCode`.
  void runBothWays(const std::vector<std::string>& command, uint32_t count, int exitCode) {
    std::vector<std::string> args = command;
    args.insert(args.end(), {"-o", (dir / "one").string()});
    const test::CommandResult one = vt(args);
    ASSERT_EQ(one.exitCode, exitCode) << one.out << one.err;
    std::vector<std::string> merge = {"merge"};
    for (uint32_t i = count; i >= 1; --i) {
      const std::string shard = "shard" + std::to_string(i);
      args = command;
      args.insert(args.end(), {"--shard", std::to_string(i) + "/" + std::to_string(count), "-o",
                               (dir / shard).string()});
      const test::CommandResult part = vt(args);
      ASSERT_TRUE(part.exitCode == 0 || part.exitCode == exitCode) << part.out << part.err;
      ASSERT_TRUE(std::filesystem::is_regular_file(dir / shard / "shard.json"));
      merge.push_back((dir / shard).string());
    }
    merge.insert(merge.end(), {"-o", (dir / "merged").string()});
    const test::CommandResult merged = vt(merge);
    ASSERT_EQ(merged.exitCode, exitCode) << merged.out << merged.err;
  }
};

// The H100's committed captures (data/gpus/nvidia-h100/captures.tar.gz, 16 captures) judged under
// its model with every pixel's set (sums of doubles over the frames), with an unreadable capture
// among them: once, and as 3 and as 5 shards.
TEST(CrosscheckShards, MergedShardsWriteWhatOneRunWrites) {
  ShardFixture f;
  const std::filesystem::path evidence =
      std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data" / "gpus" / "nvidia-h100";
  ASSERT_EQ(test::runCommand(
                "/bin/tar",
                {"-C", f.dir.path().string(), "-xzf", (evidence / "captures.tar.gz").string()},
                f.dir.path())
                .exitCode,
            0);
  const test::CommandResult demo = f.vt({"demo", "--output", (f.dir / "demo").string()});
  ASSERT_EQ(demo.exitCode, 0) << demo.err;
  std::filesystem::copy_file(f.dir / "demo" / "scene.vt", f.dir / "captures" / "scene.vt");
  std::ofstream(f.dir / "captures" / "m-unreadable.json") << "{\"format\": \"vt-capture\"}";
  const std::vector<std::string> command = {
      "crosscheck", "--captures", (f.dir / "captures").string(),
      "--all-sets", "--model",    (evidence / "model.json").string()};
  for (const uint32_t count : {3u, 5u}) {
    SCOPED_TRACE(count);
    f.runBothWays(command, count, 1);  // the unreadable capture fails the job
    expectSameFolders(f.dir / "one", f.dir / "merged", junitWithoutTimes);
    const std::string junit = test::slurp(f.dir / "merged" / "junit.xml");
    EXPECT_THAT(junit, HasSubstr("tests=\"17\" failures=\"0\" errors=\"1\""));
  }
}

struct GoldenShardFixture : ShardFixture {
  GoldenShardFixture() {
    writeSyntheticTexture(
        dir / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
    test::writeBoxRoomScene(dir.path());
    const test::CommandResult generated =
        vt({"golden", "generate", (dir / "t.vt").string(), "--mesh", (dir / "room.obj").string(),
            "--path", (dir / "path.json").string(), "--every", "4", "--profile", "llvmpipe", "-o",
            (dir / "golden").string()});
    EXPECT_EQ(generated.exitCode, 0) << generated.err;
  }
  std::vector<std::string> check(const std::string& model) {
    return {"golden",
            "check",
            (dir / "golden").string(),
            "--texture",
            (dir / "t.vt").string(),
            "--mesh",
            (dir / "room.obj").string(),
            "--path",
            (dir / "path.json").string(),
            "--model",
            model};
  }
};

std::string asIs(const std::string&, std::string bytes) { return bytes; }

// 8 recorded frames (29 frames, every 4th): passing in 10 shards (more shards than frames: two
// hold none), and failing under another arithmetic (the difference images) in 3.
TEST(GoldenShards, MergedShardsWriteWhatOneCheckWrites) {
  GoldenShardFixture f;
  for (const auto& [model, count, exitCode] : {std::tuple{"auto", 10u, 0}, {"exact", 3u, 1}}) {
    SCOPED_TRACE(model);
    f.runBothWays(f.check(model), count, exitCode);
    expectSameFolders(f.dir / "one", f.dir / "merged", asIs);
    const nlohmann::json merged =
        nlohmann::json::parse(test::slurp(f.dir / "merged" / "check.json"));
    EXPECT_EQ(merged["frames"].size(), 8u);
    // Each shard's own record says whether its part passed: under auto every part does, also the
    // shards that got no frame (ten shards of eight frames).
    for (uint32_t i = 1; i <= count && exitCode == 0; ++i) {
      const std::filesystem::path own = f.dir / ("shard" + std::to_string(i)) / "check.json";
      EXPECT_TRUE(nlohmann::json::parse(test::slurp(own))["passed"].get<bool>()) << own;
    }
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "merged" / "frame0028.difference.png"));
}

// What an evaluation measured, left out of the comparison: the times in summary.json and
// summary.md.
std::string evaluationWithoutTimes(const std::string& name, std::string bytes) {
  if (name == "summary.json") {
    nlohmann::json summary = nlohmann::json::parse(bytes);
    for (const char* key : {"view_seconds", "recolor_seconds", "wall_seconds", "jobs"})
      summary.erase(key);
    for (nlohmann::json& run : summary["runs"]) {
      run.erase("seconds");
      run.erase("times");
    }
    return summary.dump();
  }
  if (name == "summary.md") {
    // The paragraph that states the run times, and the run-time column of the tables.
    std::istringstream lines(bytes);
    std::string kept;
    for (std::string line; std::getline(lines, line);) {
      if (line.find("Run time:") != std::string::npos) continue;
      if (line.starts_with("| ") && line.ends_with(" |"))
        line.erase(line.rfind(" |", line.size() - 3));
      kept.append(line).append("\n");
    }
    return kept;
  }
  return bytes;
}

// Five configurations and a figure of two runs flown by different shards: the merged frames.csv,
// summary and plots are one run's.
TEST(EvalShards, MergedShardsWriteWhatOneEvaluationWrites) {
  ShardFixture f;
  writeSyntheticTexture(
      f.dir / "t.vt",
      {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  test::writeBoxRoomScene(f.dir.path());
  std::ofstream(f.dir / "c.json") << R"({"defaults": {"budget": 2},
    "configurations": [{"name": "A", "heuristic": "pixelsum"},
                       {"name": "B", "heuristic": "hotspot"},
                       {"name": "C", "heuristic": "random"}, {"name": "D", "budget": 4},
                       {"name": "E", "heuristic": "pixelsum*distance"}],
    "figures": [{"file": "ab.png", "title": "A and B", "measure": "wssim", "runs": ["B", "A"]}]})";
  const std::vector<std::string> command = {
      "eval",      (f.dir / "t.vt").string(),      "--mesh", (f.dir / "room.obj").string(),
      "--path",    (f.dir / "path.json").string(), "--size", "64x40",
      "--configs", (f.dir / "c.json").string()};
  for (const uint32_t count : {2u, 6u}) {
    SCOPED_TRACE(count);
    f.runBothWays(command, count, 0);
    expectSameFolders(f.dir / "one", f.dir / "merged", evaluationWithoutTimes);
    EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "merged" / "ab.png"));
    EXPECT_FALSE(std::filesystem::exists(f.dir / "shard1" / "ssim.png"));  // plots: merged only
  }
}

TEST(Merge, RefusesShardsThatAreNotOneWholeJobNamingTheFile) {
  GoldenShardFixture f;
  for (const char* shard : {"1/3", "2/3", "3/3"}) {
    std::vector<std::string> args = f.check("auto");
    const std::string folder = std::string("s") + shard[0];
    args.insert(args.end(), {"--shard", shard, "-o", (f.dir / folder).string()});
    ASSERT_EQ(f.vt(args).exitCode, 0);
  }
  std::vector<std::string> other = f.check("exact");
  other.insert(other.end(), {"--shard", "3/3", "-o", (f.dir / "exact3").string()});
  ASSERT_EQ(f.vt(other).exitCode, 1);
  const auto merge = [&](std::vector<std::string> folders) {
    std::vector<std::string> args = {"merge"};
    for (const std::string& folder : folders) args.push_back((f.dir / folder).string());
    args.insert(args.end(), {"-o", (f.dir / "merged").string()});
    return f.vt(args);
  };
  struct Case {
    std::vector<std::string> folders;
    std::string file, message;
  };
  for (const Case& c : std::vector<Case>{
           {{"s1", "s2"}, "s1/shard.json", "shard 3/3 of the job is missing"},
           {{"s1", "s2", "s2", "s3"}, "s2/shard.json", "shard 2/3 is also"},
           {{"s1", "s2", "exact3"}, "exact3/shard.json", "not a shard of the same job"}}) {
    const test::CommandResult result = merge(c.folders);
    EXPECT_EQ(result.exitCode, 1) << c.message;
    EXPECT_THAT(result.err, HasSubstr((f.dir / c.file).string() + ": " + c.message));
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_FALSE(std::filesystem::exists(f.dir / "merged"));
  }
  // A record that is not the shard's own frame, and one that is not JSON.
  const std::filesystem::path record = f.dir / "s2" / "shard.json";
  nlohmann::json json = nlohmann::json::parse(test::slurp(record));
  json["records"][0]["item"] = "frame 0";
  std::ofstream(record) << json.dump();
  test::CommandResult result = merge({"s1", "s2", "s3"});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, HasSubstr(record.string() + ": holds no record of frame "));
  std::ofstream(record) << "{\"format\": \"vt-shard\", \"version\": 1, \"command\": [";
  result = merge({"s1", "s2", "s3"});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, HasSubstr(record.string() + ": malformed shard record"));
  // A version no int holds (the fuzzer's find: it was converted to int first).
  std::ofstream(record, std::ios::trunc) << "{\"format\": \"vt-shard\", \"version\": 1e300}";
  result = merge({"s1", "s2", "s3"});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, HasSubstr(record.string() + ": shard record version 1e+300"));
  // Bad arguments: exit 2 with the usage line.
  std::vector<std::string> args = f.check("auto");
  args.insert(args.end(), {"--shard", "4/3", "-o", (f.dir / "x").string()});
  result = f.vt(args);
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_THAT(result.err, HasSubstr("\"4/3\": I must be 1 to N"));
  EXPECT_THAT(result.err, HasSubstr("Usage:"));
}

}  // namespace
}  // namespace vt
