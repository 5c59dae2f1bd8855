#include "render/precision_model_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/error.h"
#include "common/json_text.h"

namespace vt {

// Names of the enums in model files (found by argument-dependent lookup, so in this namespace).
NLOHMANN_JSON_SERIALIZE_ENUM(PrecisionProfile, {{PrecisionProfile::kExact, "exact"},
                                                {PrecisionProfile::kLlvmpipe, "llvmpipe"},
                                                {PrecisionProfile::kSoftpipe, "softpipe"}})
NLOHMANN_JSON_SERIALIZE_ENUM(Log2Arithmetic, {{Log2Arithmetic::kLlvmpipe, "llvmpipe"},
                                              {Log2Arithmetic::kSoftpipe, "softpipe"},
                                              {Log2Arithmetic::kIeee, "ieee"},
                                              {Log2Arithmetic::kBounded, "bounded"}})
NLOHMANN_JSON_SERIALIZE_ENUM(FilterArithmetic, {{FilterArithmetic::kLlvmpipe8Bit, "llvmpipe_8bit"},
                                                {FilterArithmetic::kFloat, "float"},
                                                {FilterArithmetic::kBounded, "bounded"}})

namespace {

constexpr const char* kFormat = "vt-precision-model-1";
constexpr double kMaxError = 1 << 20;

// The fields of a model file, read one by one with the field named in every error.
class Fields {
 public:
  Fields(const std::filesystem::path& file, const nlohmann::json& json)
      : file_(file), json_(json) {}

  const nlohmann::json& at(const char* field) const {
    if (!json_.contains(field))
      throw InputError(file_, std::string("field ") + field + " is missing");
    return json_.at(field);
  }
  std::string text(const char* field) const {
    const nlohmann::json& v = at(field);
    if (!v.is_string()) throw InputError(file_, std::string("field ") + field + " is not a string");
    return v.get<std::string>();
  }
  std::string choice(const char* field, std::initializer_list<const char*> values) const {
    const std::string v = text(field);
    std::string list;
    for (const char* value : values) {
      if (v == value) return v;
      list.append(list.empty() ? "" : ", ").append(value);
    }
    throw InputError(file_, std::string("field ") + field + " is '" + v + "', not one of " + list);
  }
  double number(const char* field, double lo, double hi) const {
    const nlohmann::json& v = at(field);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo ||
        v.get<double>() > hi)
      throw InputError(file_, std::string("field ") + field + " is not a number from " +
                                  std::to_string(lo) + " to " + std::to_string(hi));
    return v.get<double>();
  }
  int whole(const char* field, int lo, int hi) const {
    const nlohmann::json& v = at(field);
    if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
      throw InputError(file_, std::string("field ") + field + " is not a whole number from " +
                                  std::to_string(lo) + " to " + std::to_string(hi));
    return static_cast<int>(v.get<int64_t>());
  }

 private:
  const std::filesystem::path& file_;
  const nlohmann::json& json_;
};

template <class Enum>
Enum enumOf(const std::string& text) {
  return nlohmann::json(text).get<Enum>();
}

}  // namespace

PrecisionModel readModelFile(const std::filesystem::path& file) {
  nlohmann::json json;
  try {
    json = readJsonFile(file, "precision model");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a precision model: " + jsonErrorText(e));
  }
  if (!json.is_object()) throw InputError(file, "not a precision model: not a JSON object");
  const Fields f(file, json);
  if (f.text("format") != kFormat)
    throw InputError(file, std::string("field format is not '") + kFormat + "'");
  PrecisionModel m;
  m.name = f.text("name");
  m.renderer = f.text("renderer");
  m.arithmetic =
      enumOf<PrecisionProfile>(f.choice("arithmetic", {"exact", "llvmpipe", "softpipe"}));
  m.subpixelBits = f.whole("subpixel_bits", 1, 16);
  m.fillRulePinned = f.choice("fill_rule", {"pinned", "free"}) == "pinned";
  m.depthUlps = f.number("depth_ulps", 0, kMaxError);
  m.depthRoundsToNearest = f.choice("depth_rounding", {"nearest", "either"}) == "nearest";
  m.attributeUlps = f.number("attribute_ulps", 0, kMaxError);
  m.log2 = enumOf<Log2Arithmetic>(f.choice("log2", {"llvmpipe", "softpipe", "ieee", "bounded"}));
  m.log2AbsoluteError = f.number("log2_absolute_error", 0, 1);
  m.log2Ulps = f.number("log2_ulps", 0, kMaxError);
  m.sqrtUlps = f.number("sqrt_ulps", 0, kMaxError);
  m.arithmeticUlps = f.number("arithmetic_ulps", 0, kMaxError);
  m.filter = enumOf<FilterArithmetic>(f.choice("filter", {"llvmpipe_8bit", "float", "bounded"}));
  m.subTexelBits = f.whole("sub_texel_bits", 0, 16);
  m.filterErrorUnits = f.number("filter_error_units", 0, 255);
  m.colorRoundsToNearest = f.choice("color_conversion", {"nearest", "either"}) == "nearest";
  m.denormalsPinned = f.choice("denormals", {"pinned", "free"}) == "pinned";
  const nlohmann::json& sources = f.at("sources");
  if (!sources.is_object()) throw InputError(file, "field sources is not an object");
  for (const auto& [parameter, source] : sources.items()) {
    if (!source.is_string())
      throw InputError(file, "field sources." + parameter + " is not a string");
    m.sources[parameter] = source.get<std::string>();
  }
  if (json.contains("calibration")) {
    const nlohmann::json& calibration = json.at("calibration");
    if (!calibration.is_object() || !calibration.contains("gl_version") ||
        !calibration.at("gl_version").is_string())
      throw InputError(file, "field calibration.gl_version is missing or not a string");
    m.glVersion = calibration.at("gl_version").get<std::string>();
  }
  if (m.filter == FilterArithmetic::kBounded && m.subTexelBits == 0)
    throw InputError(file, "field sub_texel_bits is 0 for a bounded filter");
  if (m.log2 != Log2Arithmetic::kBounded && m.log2 != log2Of(m.arithmetic))
    throw InputError(file, "field log2 is '" + nlohmann::json(m.log2).get<std::string>() +
                               "' under " + toString(m.arithmetic) +
                               " arithmetic (the oracle computes that arithmetic's log2; a "
                               "pinned log2 must be it)");
  return m;
}

std::string modelJson(const PrecisionModel& m) {
  const nlohmann::ordered_json json = {
      {"format", kFormat},
      {"name", m.name},
      {"renderer", m.renderer},
      {"arithmetic", nlohmann::json(m.arithmetic)},
      {"subpixel_bits", m.subpixelBits},
      {"fill_rule", m.fillRulePinned ? "pinned" : "free"},
      {"depth_ulps", m.depthUlps},
      {"depth_rounding", m.depthRoundsToNearest ? "nearest" : "either"},
      {"attribute_ulps", m.attributeUlps},
      {"log2", nlohmann::json(m.log2)},
      {"log2_absolute_error", m.log2AbsoluteError},
      {"log2_ulps", m.log2Ulps},
      {"sqrt_ulps", m.sqrtUlps},
      {"arithmetic_ulps", m.arithmeticUlps},
      {"filter", nlohmann::json(m.filter)},
      {"sub_texel_bits", m.subTexelBits},
      {"filter_error_units", m.filterErrorUnits},
      {"color_conversion", m.colorRoundsToNearest ? "nearest" : "either"},
      {"denormals", m.denormalsPinned ? "pinned" : "free"},
      {"sources", m.sources}};
  return json.dump(2) + "\n";
}

std::string calibrationMismatch(const PrecisionModel& model, const std::string& glRenderer,
                                const std::string& glVersion) {
  if (model.renderer.empty() && model.glVersion.empty()) return "";
  if (model.renderer != glRenderer)
    return "warning: precision model '" + model.name + "' was measured on " + model.renderer +
           ", this is " + glRenderer + ": run vt calibrate here";
  if (!model.glVersion.empty() && model.glVersion != glVersion)
    return "warning: precision model '" + model.name + "' was measured with " + model.glVersion +
           ", this driver is " + glVersion + ": re-run vt calibrate";
  return "";
}

std::optional<std::filesystem::path> measuredModelFile(const std::string& glRenderer) {
  const char* folder = std::getenv("VT_PRECISION_MODELS");
  if (!folder || !*folder) return std::nullopt;
  std::error_code error;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  if (error)
    throw InputError(folder,
                     "cannot list the precision models (VT_PRECISION_MODELS): " + error.message());
  std::sort(files.begin(), files.end());
  for (const std::filesystem::path& file : files)
    if (readModelFile(file).renderer == glRenderer) return file;
  return std::nullopt;
}

PrecisionModel resolveModel(const std::string& nameOrFile, const std::string& glRenderer) {
  if (nameOrFile == "auto") {
    if (const auto file = measuredModelFile(glRenderer)) return readModelFile(*file);
    return modelForRenderer(glRenderer);
  }
  if (isModelName(nameOrFile)) return namedModel(nameOrFile);
  return readModelFile(nameOrFile);
}

}  // namespace vt
