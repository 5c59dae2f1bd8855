#include "render/precision_model_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "common/error.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "render/arithmetic_points.h"

namespace vt {

namespace {

constexpr const char* kFormat = "vt-precision-model-2";
constexpr const char* kFormatVersion1 = "vt-precision-model-1";
constexpr double kMaxError = 1 << 20;

// The fields of a model file, read one by one with the field named in every error.
class Fields {
 public:
  Fields(const std::filesystem::path& file, const nlohmann::json& json, std::string prefix = "")
      : file_(file), json_(json), prefix_(std::move(prefix)) {}

  const nlohmann::json& at(const char* field) const {
    if (!json_.contains(field)) throw InputError(file_, "field " + prefix_ + field + " is missing");
    read_.insert(field);
    return json_.at(field);
  }
  // A field nobody read would judge under a default the file's author never chose (a misspelt
  // bound, a member's parameter under another member): refused, as capture manifests refuse it.
  void refuseUnread() const {
    for (const auto& item : json_.items())
      if (!read_.count(item.key()))
        throw InputError(
            file_, "field " + prefix_ + item.key() + " is not a field of a precision model here");
  }
  InputError failure(const std::string& text) const { return InputError(file_, text); }
  const std::filesystem::path& file() const { return file_; }
  bool has(const char* field) const { return json_.contains(field); }
  // The object in `field`, its fields named with it.
  Fields object(const char* field) const {
    const nlohmann::json& v = at(field);
    if (!v.is_object()) throw InputError(file_, "field " + prefix_ + field + " is not an object");
    return Fields(file_, v, prefix_ + field + ".");
  }
  bool flag(const char* field) const {
    const nlohmann::json& v = at(field);
    if (!v.is_boolean())
      throw InputError(file_, "field " + prefix_ + field + " is not true or false");
    return v.get<bool>();
  }
  template <class Enum, size_t N>
  Enum named(const char* field, const EnumNames<Enum, N>& names) const {
    const std::string v = text(field);
    if (const auto value = findByName(names, v)) return *value;
    throw InputError(
        file_, "field " + prefix_ + field + " is '" + v + "', not one of " + joinedNames(names));
  }
  std::string text(const char* field) const {
    const nlohmann::json& v = at(field);
    if (!v.is_string()) throw InputError(file_, "field " + prefix_ + field + " is not a string");
    return v.get<std::string>();
  }
  std::string choice(const char* field, std::initializer_list<const char*> values) const {
    const std::string v = text(field);
    std::string list;
    for (const char* value : values) {
      if (v == value) return v;
      list.append(list.empty() ? "" : ", ").append(value);
    }
    throw InputError(file_, "field " + prefix_ + field + " is '" + v + "', not one of " + list);
  }
  double number(const char* field, double lo, double hi) const {
    const nlohmann::json& v = at(field);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo ||
        v.get<double>() > hi)
      throw InputError(file_, "field " + prefix_ + field + " is not a number from " +
                                  std::to_string(lo) + " to " + std::to_string(hi));
    return v.get<double>();
  }
  // The ten weights of a palette's weights member, each a whole number from 0 to 2^12.
  AlphaWeights weights(const char* field) const {
    const nlohmann::json& v = at(field);
    AlphaWeights w{};
    if (!v.is_array() || v.size() != w.size())
      throw InputError(file_, "field " + prefix_ + field + " is not a list of " +
                                  std::to_string(w.size()) + " weights");
    for (size_t i = 0; i < w.size(); ++i) {
      if (!v[i].is_number_integer() || v[i].get<int64_t>() < 0 ||
          v[i].get<int64_t>() > (1 << kPaletteWeightBits))
        throw InputError(file_, "field " + prefix_ + field + "[" + std::to_string(i) +
                                    "] is not a whole number from 0 to " +
                                    std::to_string(1 << kPaletteWeightBits));
      w[i] = static_cast<uint16_t>(v[i].get<int64_t>());
    }
    return w;
  }
  int whole(const char* field, int lo, int hi) const {
    const nlohmann::json& v = at(field);
    if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
      throw InputError(file_, "field " + prefix_ + field + " is not a whole number from " +
                                  std::to_string(lo) + " to " + std::to_string(hi));
    return static_cast<int>(v.get<int64_t>());
  }

 private:
  const std::filesystem::path& file_;
  const nlohmann::json& json_;
  std::string prefix_;
  mutable std::set<std::string> read_;
};

// A measured table (render/measured_table.h) the arithmetic names under its function's key, from
// beside the model file; none where the key is absent.
std::shared_ptr<const MeasuredTable> readTable(const Fields& f, TabledFunction function) {
  const char* key = tableKey(function);
  if (!f.has(key)) return nullptr;
  const Fields table = f.object(key);
  const std::string field = std::string("field arithmetic.") + key;
  const std::string checksum = table.text("checksum");
  if (checksum.size() != 16 || checksum.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw table.failure(field + ".checksum is not 16 hexadecimal digits");
  const std::string name = tableFileName(function, checksum);
  if (table.text("table") != name)
    throw table.failure(field + ".table is not " + name +
                        " (the table is named by its checksum, beside the model)");
  table.refuseUnread();
  return MeasuredTable::read(function, f.file().parent_path() / name, checksum);
}

Arithmetic readArithmetic(const Fields& f) {
  Arithmetic a;
  a.fusedViewport = f.choice("viewport", {"fused", "unfused"}) == "fused";
  const Fields coverage = f.object("coverage");
  a.coverage.rule = coverage.named("rule", kCoverageRuleNames);
  a.coverage.subpixelBits = coverage.whole("subpixel_bits", 1, 16);
  a.coverage.rounding = coverage.named("rounding", kSnapRoundingNames);
  a.coverage.leftEdgesIn = coverage.flag("left_edges_in");
  a.coverage.bottomEdgesIn = coverage.flag("bottom_edges_in");
  coverage.refuseUnread();
  a.planeSetup = f.named("plane_setup", kPlaneSetupNames);
  // Absent from files written before the member existed, which all set up through the float
  // positions.
  if (f.has("plane_positions")) {
    a.planePositions = f.named("plane_positions", kPlanePositionsNames);
    if (a.planePositions == PlanePositions::kSnapped &&
        a.coverage.rule != CoverageRule::kSnappedEdges)
      throw f.failure("field arithmetic.plane_positions is 'snapped' but the coverage (" +
                      std::string(nameOf(kCoverageRuleNames, a.coverage.rule)) +
                      ") snaps no position");
  }
  a.planeEvaluation = f.named("plane_evaluation", kPlaneEvaluationNames);
  a.perspective = f.named("perspective", kPerspectiveNames);
  a.reciprocal.table = readTable(f, TabledFunction::kReciprocal);
  if (a.reciprocal.table && a.perspective != Perspective::kReciprocalTimes)
    throw f.failure("field arithmetic.reciprocal is set, but the perspective (" +
                    std::string(nameOf(kPerspectiveNames, a.perspective)) +
                    ") takes no reciprocal");
  const Fields depth = f.object("depth");
  a.depth.offsetAndClamp = depth.flag("offset_and_clamp");
  a.depth.z24 = depth.named("z24", kZ24ConversionNames);
  depth.refuseUnread();
  a.log2 = f.named("log2", kLog2FormNames);
  a.sqrt.table = readTable(f, TabledFunction::kSqrt);
  a.log2Table.table = readTable(f, TabledFunction::kLog2);
  const Fields filter = f.object("filter");
  a.filter.weights = filter.named("weights", kFilterWeightsNames);
  // The corner-weight member's parameters, written for it alone.
  if (a.filter.weights == FilterWeights::kFixedPointCorners) {
    a.filter.coordinateBits = filter.whole("coordinate_bits", 8, 30);
    a.filter.weightBits = filter.whole("weight_bits", 1, 12);
    if (a.filter.weightBits > a.filter.coordinateBits)
      throw filter.failure("field weight_bits is more than coordinate_bits");
    a.filter.positionRounding = filter.named("position_rounding", kPositionRoundingNames);
    a.filter.output = filter.named("output", kFilterOutputNames);
  }
  a.filter.fusedLerp = filter.flag("fused_lerp");
  a.filter.fusedCoordinate = filter.flag("fused_coordinate");
  // Absent from files written before the member existed, which all rounded to nearest.
  a.filter.lerpRounding = filter.has("lerp_rounding")
                              ? filter.named("lerp_rounding", kLerpRoundingNames)
                              : LerpRounding::kNearest;
  filter.refuseUnread();
  a.texelConversion = f.named("texel_conversion", kUnormConversionNames);
  a.flushDenormals = f.choice("denormals", {"flushed", "kept"}) == "flushed";
  // Absent from files written before block formats, which decoded to nearest.
  if (f.has("block_decoding")) {
    const Fields decoding = f.object("block_decoding");
    a.blockDecoding.colour = decoding.named("colour", kPaletteRuleNames);
    a.blockDecoding.alpha = decoding.named("alpha", kPaletteRuleNames);
    if (!isAlphaRule(a.blockDecoding.alpha))
      throw decoding.failure("field alpha is '" +
                             std::string(nameOf(kPaletteRuleNames, a.blockDecoding.alpha)) +
                             "', a rule for colour palettes only");
    if (!isColourRule(a.blockDecoding.colour))
      throw decoding.failure("field colour is '" +
                             std::string(nameOf(kPaletteRuleNames, a.blockDecoding.colour)) +
                             "', a rule for alpha palettes only");
    if (a.blockDecoding.alpha == PaletteRule::kWeights)
      a.blockDecoding.alphaWeights = decoding.weights("alpha_weights");
    decoding.refuseUnread();
  }
  // Absent from files written before the member existed: rounded to nearest.
  if (f.has("colour_conversion")) {
    const Fields conversion = f.object("colour_conversion");
    a.colourConversion.rule = conversion.named("rule", kColourConversionRuleNames);
    if (a.colourConversion.rule == ColourConversionRule::kQuantized) {
      a.colourConversion.bits = conversion.whole("bits", 8, 24);
      a.colourConversion.bias = conversion.whole("bias", 0, (1 << a.colourConversion.bits) - 1);
    }
    conversion.refuseUnread();
  }
  f.refuseUnread();
  return a;
}

// Version 1 files name a point, and their log2 and filter fields a member (arithmetic_points.h).
void readVersion1(const Fields& f, PrecisionModel& m) {
  const std::string point = f.text("arithmetic"), log2 = f.text("log2"), filter = f.text("filter");
  if (!readVersion1Arithmetic(point, log2, filter, m))
    throw f.failure("fields arithmetic, log2 and filter ('" + point + "', '" + log2 + "', '" +
                    filter + "') are not a version 1 model's");
}

// The evidence `vt calibrate` writes under "calibration" (calibration.cpp): judging reads only the
// driver's version, the rest is checked for its shape so that a damaged record is not trusted.
std::string readCalibration(const Fields& c) {
  (void)c.text("gl_renderer");
  (void)c.text("gl_vendor");
  (void)c.text("point");
  const nlohmann::json& parameters = c.at("parameters");
  if (!parameters.is_array()) throw c.failure("field calibration.parameters is not a list");
  for (const nlohmann::json& parameter : parameters)
    if (!parameter.is_object())
      throw c.failure("field calibration.parameters holds an entry that is not an object");
  std::string version = c.text("gl_version");
  c.refuseUnread();
  return version;
}

}  // namespace

void writeModelFiles(const std::filesystem::path& file, const Arithmetic& arithmetic,
                     const std::string& json) {
  for (const auto& table :
       {arithmetic.reciprocal.table, arithmetic.sqrt.table, arithmetic.log2Table.table})
    if (table)
      writeFileAtomically(file.parent_path() / tableFileName(table->function(), table->checksum()),
                          table->fileBytes());
  writeFileAtomically(file, json);
}

nlohmann::ordered_json arithmeticJson(const Arithmetic& a) {
  nlohmann::ordered_json json = {
      {"viewport", a.fusedViewport ? "fused" : "unfused"},
      {"coverage",
       {{"rule", nameOf(kCoverageRuleNames, a.coverage.rule)},
        {"subpixel_bits", a.coverage.subpixelBits},
        {"rounding", nameOf(kSnapRoundingNames, a.coverage.rounding)},
        {"left_edges_in", a.coverage.leftEdgesIn},
        {"bottom_edges_in", a.coverage.bottomEdgesIn}}},
      {"plane_setup", nameOf(kPlaneSetupNames, a.planeSetup)},
      {"plane_evaluation", nameOf(kPlaneEvaluationNames, a.planeEvaluation)},
      {"perspective", nameOf(kPerspectiveNames, a.perspective)},
      {"depth",
       {{"offset_and_clamp", a.depth.offsetAndClamp},
        {"z24", nameOf(kZ24ConversionNames, a.depth.z24)}}},
      {"log2", nameOf(kLog2FormNames, a.log2)},
      {"filter",
       {{"weights", nameOf(kFilterWeightsNames, a.filter.weights)},
        {"fused_lerp", a.filter.fusedLerp},
        {"fused_coordinate", a.filter.fusedCoordinate},
        {"lerp_rounding", nameOf(kLerpRoundingNames, a.filter.lerpRounding)}}},
      {"texel_conversion", nameOf(kUnormConversionNames, a.texelConversion)},
      {"denormals", a.flushDenormals ? "flushed" : "kept"},
      {"block_decoding",
       {{"colour", nameOf(kPaletteRuleNames, a.blockDecoding.colour)},
        {"alpha", nameOf(kPaletteRuleNames, a.blockDecoding.alpha)}}}};
  // Members measured on a GPU carry their parameters; files of the other members stay as they
  // were written before these existed.
  if (a.filter.weights == FilterWeights::kFixedPointCorners) {
    nlohmann::ordered_json& filter = json["filter"];
    filter["coordinate_bits"] = a.filter.coordinateBits;
    filter["weight_bits"] = a.filter.weightBits;
    filter["position_rounding"] = nameOf(kPositionRoundingNames, a.filter.positionRounding);
    filter["output"] = nameOf(kFilterOutputNames, a.filter.output);
  }
  if (a.planePositions == PlanePositions::kSnapped) json["plane_positions"] = "snapped";
  for (const auto& table : {a.reciprocal.table, a.sqrt.table, a.log2Table.table})
    if (table)
      json[tableKey(table->function())] = {
          {"table", tableFileName(table->function(), table->checksum())},
          {"checksum", table->checksum()}};
  if (a.blockDecoding.alpha == PaletteRule::kWeights)
    json["block_decoding"]["alpha_weights"] = a.blockDecoding.alphaWeights;
  if (a.colourConversion.rule != ColourConversionRule::kNearest)
    json["colour_conversion"] = {
        {"rule", nameOf(kColourConversionRuleNames, a.colourConversion.rule)},
        {"bits", a.colourConversion.bits},
        {"bias", a.colourConversion.bias}};
  return json;
}

PrecisionModel readModelFile(const std::filesystem::path& file) {
  nlohmann::json json;
  try {
    json = readJsonFile(file, "precision model");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a precision model: " + jsonErrorText(e));
  }
  if (!json.is_object()) throw InputError(file, "not a precision model: not a JSON object");
  const Fields f(file, json);
  const std::string format = f.choice("format", {kFormat, kFormatVersion1});
  PrecisionModel m;
  m.name = f.text("name");
  m.renderer = f.text("renderer");
  if (format == kFormatVersion1) {
    readVersion1(f, m);
  } else {
    m.arithmetic = readArithmetic(f.object("arithmetic"));
    m.log2Pinned = f.choice("log2", {"pinned", "bounded"}) == "pinned";
    m.filterPinned = f.choice("filter", {"pinned", "bounded"}) == "pinned";
  }
  m.subpixelBits = f.whole("subpixel_bits", 1, 16);
  m.fillRulePinned = f.choice("fill_rule", {"pinned", "free"}) == "pinned";
  m.depthUlps = f.number("depth_ulps", 0, kMaxError);
  m.depthRoundsToNearest = f.choice("depth_rounding", {"nearest", "either"}) == "nearest";
  m.attributeUlps = f.number("attribute_ulps", 0, kMaxError);
  m.log2AbsoluteError = f.number("log2_absolute_error", 0, 1);
  m.log2Ulps = f.number("log2_ulps", 0, kMaxError);
  m.sqrtUlps = f.number("sqrt_ulps", 0, kMaxError);
  m.arithmeticUlps = f.number("arithmetic_ulps", 0, kMaxError);
  m.subTexelBits = f.whole("sub_texel_bits", 0, 16);
  m.filterErrorUnits = f.number("filter_error_units", 0, 255);
  // "nearest" in files of the nearest member (all written before measured members existed),
  // "pinned" for a measured one.
  const std::string colour = f.choice("color_conversion", {"nearest", "pinned", "either"});
  m.colorPinned = colour != "either";
  if (colour != "either" && (colour == "nearest") != (m.arithmetic.colourConversion.rule ==
                                                      ColourConversionRule::kNearest))
    throw f.failure(
        "field color_conversion is '" + colour + "' but the arithmetic's is '" +
        std::string(nameOf(kColourConversionRuleNames, m.arithmetic.colourConversion.rule)) + "'");
  m.denormalsPinned = f.choice("denormals", {"pinned", "free"}) == "pinned";
  // Absent from files written before block formats: pinned, as they decoded one way.
  m.decodingPinned =
      !f.has("block_decoding") || f.choice("block_decoding", {"pinned", "free"}) == "pinned";
  const nlohmann::json& sources = f.at("sources");
  if (!sources.is_object()) throw InputError(file, "field sources is not an object");
  for (const auto& [parameter, source] : sources.items()) {
    if (!source.is_string())
      throw InputError(file, "field sources." + parameter + " is not a string");
    m.sources[parameter] = source.get<std::string>();
  }
  if (f.has("calibration")) m.glVersion = readCalibration(f.object("calibration"));
  f.refuseUnread();
  if (m.fillRulePinned && m.arithmetic.coverage.rule == CoverageRule::kSnappedEdges &&
      m.subpixelBits != m.arithmetic.coverage.subpixelBits)
    throw InputError(file, "field subpixel_bits is " + std::to_string(m.subpixelBits) +
                               " but the pinned coverage snaps to " +
                               std::to_string(m.arithmetic.coverage.subpixelBits) + " bits");
  if (!m.filterPinned && m.subTexelBits == 0)
    throw InputError(file, "field sub_texel_bits is 0 for a bounded filter");
  // A model wider than the specification would pass a non-conformant implementation.
  if (const std::string beyond = beyondGl45(m); !beyond.empty())
    throw InputError(file, "allows " + beyond);
  return m;
}

std::string modelJson(const PrecisionModel& m) {
  const nlohmann::ordered_json json = {
      {"format", kFormat},
      {"name", m.name},
      {"renderer", m.renderer},
      {"arithmetic", arithmeticJson(m.arithmetic)},
      {"subpixel_bits", m.subpixelBits},
      {"fill_rule", m.fillRulePinned ? "pinned" : "free"},
      {"depth_ulps", m.depthUlps},
      {"depth_rounding", m.depthRoundsToNearest ? "nearest" : "either"},
      {"attribute_ulps", m.attributeUlps},
      {"log2", m.log2Pinned ? "pinned" : "bounded"},
      {"log2_absolute_error", m.log2AbsoluteError},
      {"log2_ulps", m.log2Ulps},
      {"sqrt_ulps", m.sqrtUlps},
      {"arithmetic_ulps", m.arithmeticUlps},
      {"filter", m.filterPinned ? "pinned" : "bounded"},
      {"sub_texel_bits", m.subTexelBits},
      {"filter_error_units", m.filterErrorUnits},
      {"color_conversion", !m.colorPinned ? "either"
                           : m.arithmetic.colourConversion.rule == ColourConversionRule::kNearest
                               ? "nearest"
                               : "pinned"},
      {"denormals", m.denormalsPinned ? "pinned" : "free"},
      {"block_decoding", m.decodingPinned ? "pinned" : "free"},
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
  // Without a GL context to fingerprint (calibrate/fingerprint.h), a renderer's name is no
  // evidence: a measured model of it, else the specification.
  if (nameOrFile == "auto") {
    if (const auto file = measuredModelFile(glRenderer)) return readModelFile(*file);
    return gl45Model();
  }
  if (isModelName(nameOrFile)) return namedModel(nameOrFile);
  return readModelFile(nameOrFile);
}

}  // namespace vt
