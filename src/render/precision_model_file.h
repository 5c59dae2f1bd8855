#pragma once
// Precision models as JSON files (a model measured on one implementation, or written by hand):
//
//   {"format": "vt-precision-model-1", "name": "...", "renderer": "<GL_RENDERER it describes>",
//    "arithmetic": "exact" | "llvmpipe",
//    "subpixel_bits": 1..16, "fill_rule": "pinned" | "free",
//    "depth_ulps": >= 0, "depth_rounding": "nearest" | "either",
//    "attribute_ulps": >= 0,
//    "log2": "llvmpipe" | "ieee" | "bounded", "log2_absolute_error": >= 0, "log2_ulps": >= 0,
//    "sqrt_ulps": >= 0, "arithmetic_ulps": >= 0,
//    "filter": "llvmpipe_8bit" | "float" | "bounded", "sub_texel_bits": 0..16,
//    "filter_error_units": >= 0,
//    "color_conversion": "nearest" | "either", "denormals": "pinned" | "free",
//    "sources": {"<parameter>": "<where its value comes from>", ...}}
//
// Every field is required; a missing, misspelt or out-of-range one is refused with the file and
// the field named. Errors in ulps and units are at most 2^20 (a bound that loose would accept
// anything, and is a mistake).

#include <filesystem>
#include <optional>
#include <string>

#include "render/precision_model.h"

namespace vt {

PrecisionModel readModelFile(const std::filesystem::path& file);
std::string modelJson(const PrecisionModel& model);

// A measured model may carry "calibration": {"gl_version": ...} (`vt calibrate` writes it with its
// evidence); it is read into PrecisionModel::glVersion.

// A one-line warning when `model` was measured on another implementation or driver version than
// the current one (GL_RENDERER, GL_VERSION): a driver update can change what the model pins, so
// re-calibrate. Empty when they agree or the model is a shipped one.
std::string calibrationMismatch(const PrecisionModel& model, const std::string& glRenderer,
                                const std::string& glVersion);

// The measured model for an implementation: the first model file (by name) in the folder
// $VT_PRECISION_MODELS whose renderer is `glRenderer`; none when the variable is unset or no file
// matches. Files there that are not models are refused (InputError naming the file).
std::optional<std::filesystem::path> measuredModelFile(const std::string& glRenderer);

// A model by name (llvmpipe, exact, gl45), a model file, or "auto": the measured model of
// `glRenderer` (measuredModelFile), else modelForRenderer (llvmpipe on llvmpipe with FMA, else
// gl45).
PrecisionModel resolveModel(const std::string& nameOrFile, const std::string& glRenderer);

}  // namespace vt
