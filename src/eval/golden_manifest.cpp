#include "eval/golden_manifest.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/error.h"
#include "common/json_text.h"
#include "render/arithmetic_points.h"

namespace vt {
namespace {

constexpr const char* kFormat = "vt-golden 1";

// Whole numbers only: a float converted to int out of its range is undefined.
int whole(const nlohmann::json& value, const char* what) {
  if (!value.is_number_integer() || value.get<int64_t>() < 0 || value.get<int64_t>() > 1 << 30)
    throw std::invalid_argument(std::string(what) + " is not a whole number from 0 to 2^30");
  return static_cast<int>(value.get<int64_t>());
}

}  // namespace

std::string GoldenManifest::text() const {
  nlohmann::json recorded = nlohmann::json::array();
  for (const GoldenFrame& f : frames)
    recorded.push_back({{"frame", f.frame},
                        {"color", f.color},
                        {"need", f.need},
                        {"rmse", f.rmse},
                        {"ssim", f.ssim},
                        {"wssim", f.wssim},
                        {"image", f.image}});
  const nlohmann::json json = {{"format", kFormat},
                               {"texture", texture},
                               {"texture_identity", textureIdentity},
                               {"mesh", mesh},
                               {"mesh_checksum", meshChecksum},
                               {"path", path},
                               {"path_checksum", pathChecksum},
                               {"configuration", configuration.toJson()},
                               {"width", viewport.width},
                               {"height", viewport.height},
                               {"profile", arithmeticLabel(profile)},
                               {"every", every},
                               {"frames", recorded}};
  return json.dump(1) + "\n";
}

GoldenManifest GoldenManifest::read(const std::filesystem::path& file) {
  GoldenManifest m;
  try {
    const nlohmann::json json = readJsonFile(file, "golden set");
    if (json.at("format") != kFormat)
      throw std::invalid_argument("format is not '" + std::string(kFormat) + "'");
    m.texture = json.value("texture", "");
    m.mesh = json.value("mesh", "");
    m.path = json.value("path", "");
    m.textureIdentity = json.at("texture_identity").get<std::string>();
    m.meshChecksum = json.at("mesh_checksum").get<std::string>();
    m.pathChecksum = json.at("path_checksum").get<std::string>();
    m.configuration = FlightConfiguration::fromJson(json.at("configuration"), {});
    m.viewport = {whole(json.at("width"), "width"), whole(json.at("height"), "height")};
    m.profile = arithmeticPoint(json.at("profile").get<std::string>());
    m.every = whole(json.at("every"), "every");
    for (const nlohmann::json& f : json.at("frames"))
      m.frames.push_back({.frame = whole(f.at("frame"), "a frame number"),
                          .color = f.at("color").get<std::string>(),
                          .need = f.at("need").get<std::string>(),
                          .rmse = f.at("rmse").get<double>(),
                          .ssim = f.at("ssim").get<double>(),
                          .wssim = f.at("wssim").get<double>(),
                          .image = f.at("image").get<std::string>()});
    if (m.every < 1 || m.viewport.width < 1 || m.viewport.height < 1 || m.viewport.width > 16384 ||
        m.viewport.height > 16384 || m.frames.empty())
      throw std::invalid_argument("size, every or frames out of range");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a golden set: " + jsonErrorText(e));
  } catch (const std::invalid_argument& e) {
    throw InputError(file, std::string("not a golden set: ") + e.what());
  }
  return m;
}

}  // namespace vt
