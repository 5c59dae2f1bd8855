#include "eval/golden_report.h"

#include <string>

#include "common/error.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "eval/flight_records.h"
#include "render/arithmetic_points.h"

namespace vt {
namespace {

constexpr const char* kGoldenShardCommand = "golden check";

nlohmann::json frameCheckJson(const GoldenFrameCheck& frame) {
  return {{"frame", frame.frame},
          {"color_matches", frame.colorMatches},
          {"need_matches", frame.needMatches},
          {"quality_matches", frame.qualityMatches},
          {"pixels_differing", frame.pixelsDiffering},
          {"max_color_difference", frame.maxColorDifference},
          {"explained", frame.explained},
          {"unexplained", frame.unexplained},
          {"ambiguous", frame.ambiguous},
          {"passed", frame.passed}};
}

GoldenFrameCheck frameCheckFromJson(const nlohmann::json& json) {
  GoldenFrameCheck frame;
  json.at("frame").get_to(frame.frame);
  json.at("color_matches").get_to(frame.colorMatches);
  json.at("need_matches").get_to(frame.needMatches);
  json.at("quality_matches").get_to(frame.qualityMatches);
  json.at("pixels_differing").get_to(frame.pixelsDiffering);
  json.at("max_color_difference").get_to(frame.maxColorDifference);
  json.at("explained").get_to(frame.explained);
  json.at("unexplained").get_to(frame.unexplained);
  json.at("ambiguous").get_to(frame.ambiguous);
  json.at("passed").get_to(frame.passed);
  return frame;
}

std::string frameItem(int frame) { return "frame " + std::to_string(frame); }

std::filesystem::path differenceImage(int frame) {
  return std::filesystem::path(frameImageName(frame)).replace_extension(".difference.png");
}

// check.json, the profile by its label.
void writeCheckFile(const std::filesystem::path& report, const std::filesystem::path& golden,
                    const GoldenCheck& check, const std::string& profile) {
  nlohmann::json frames = nlohmann::json::array();
  for (const GoldenFrameCheck& frame : check.frames) frames.push_back(frameCheckJson(frame));
  writeFileAtomically(report / "check.json", nlohmann::json{{"golden", golden.string()},
                                                            {"backend", check.backend},
                                                            {"profile", profile},
                                                            {"model", check.model},
                                                            {"passed", check.passed()},
                                                            {"frames", frames}}
                                                     .dump(2) +
                                                 "\n");
}

}  // namespace

void writeCheckReport(const std::filesystem::path& report, const std::filesystem::path& golden,
                      const GoldenCheck& check) {
  writeCheckFile(report, golden, check, arithmeticLabel(check.profile));
}

void writeGoldenCheckShard(const std::filesystem::path& report, const GoldenManifest& golden,
                           const GoldenCheckFiles& files, Shard shard, const GoldenCheck& check) {
  ShardFile record{{}, kGoldenShardCommand, shard, {}, {}, nlohmann::json::array()};
  record.inputs = {{"golden", files.golden.string()},
                   {"texture", files.texture.string()},
                   {"mesh", files.mesh.string()},
                   {"path", files.path.string()},
                   {"backend", check.backend},
                   {"profile", arithmeticLabel(check.profile)},
                   {"model", check.model}};
  for (const GoldenFrame& frame : golden.frames) record.items.push_back(frameItem(frame.frame));
  for (const GoldenFrameCheck& frame : check.frames)
    record.records.push_back({{"item", frameItem(frame.frame)}, {"check", frameCheckJson(frame)}});
  writeShardFile(report, record);
}

bool isGoldenCheckShard(const ShardFile& shard) { return shard.command == kGoldenShardCommand; }

GoldenCheck mergeGoldenCheckShards(const std::vector<ShardFile>& shards,
                                   const std::filesystem::path& output) {
  const ShardFile& first = shards.front();
  GoldenCheck check;
  std::string golden, profile;
  try {
    golden = first.inputs.at("golden").get<std::string>();
    check.backend = first.inputs.at("backend").get<std::string>();
    profile = first.inputs.at("profile").get<std::string>();
    check.model = first.inputs.at("model").get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(first.file, "malformed inputs of a golden check: " + jsonErrorText(e));
  }
  TemporaryFolder staging(output, "check.json");
  for (const ShardFile& shard : shards) {
    const auto [begin, end] = shard.shard.block(shard.items.size());
    if (shard.records.size() != end - begin)
      throw InputError(shard.file, "holds " + std::to_string(shard.records.size()) +
                                       " frame records, shard " + shard.shard.text() + " checks " +
                                       std::to_string(end - begin));
    for (size_t k = begin; k < end; ++k) {
      const nlohmann::json& record = shard.records[k - begin];
      try {
        if (record.at("item") != shard.items[k])
          throw InputError(shard.file, "holds no record of " + shard.items[k]);
        check.frames.push_back(frameCheckFromJson(record.at("check")));
      } catch (const nlohmann::json::exception& e) {
        throw InputError(shard.file,
                         "malformed record of " + shard.items[k] + ": " + jsonErrorText(e));
      }
      const GoldenFrameCheck& frame = check.frames.back();
      if (!frame.passed)
        copyShardFile(shard, differenceImage(frame.frame).string(), "difference image",
                      staging.path());
    }
  }
  writeCheckFile(staging.path(), golden, check, profile);
  staging.commit();
  return check;
}

}  // namespace vt
