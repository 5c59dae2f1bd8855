#pragma once
// Precision models as JSON files (a model measured on one implementation, or written by hand):
//
//   {"format": "vt-precision-model-2", "name": "...", "renderer": "<GL_RENDERER it describes>",
//    "arithmetic": {one member per family of render/arithmetic.h, e.g. "log2": "libm"},
//    "subpixel_bits": 1..16, "fill_rule": "pinned" | "free",
//    "depth_ulps": >= 0, "depth_rounding": "nearest" | "either",
//    "attribute_ulps": >= 0,
//    "log2": "pinned" | "bounded", "log2_absolute_error": >= 0, "log2_ulps": >= 0,
//    "sqrt_ulps": >= 0, "arithmetic_ulps": >= 0,
//    "filter": "pinned" | "bounded", "sub_texel_bits": 0..16,
//    "filter_error_units": >= 0,
//    "color_conversion": "nearest" | "either", "denormals": "pinned" | "free",
//    "sources": {"<parameter>": "<where its value comes from>", ...}}
//
// depth_ulps and attribute_ulps count units of 2^-23 relative to the terms their computation sums
// (precision_model.h); a file written before depth_ulps became relative (2026-11) only reads wider.
// Every field is required; a missing, misspelt or out-of-range one is refused with the file and
// the field named, and so is a model that allows more than gl45 (precision_model.h, beyondGl45).
// Version 1 files ("vt-precision-model-1": "arithmetic" names a point, "log2" and "filter" name
// members or "bounded") are still read.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/precision_model.h"

namespace vt {

// An arithmetic as the model file's "arithmetic" object.
nlohmann::ordered_json arithmeticJson(const Arithmetic& arithmetic);

// A model's measured tables (render/measured_table.h) lie beside it as FUNCTION-CHECKSUM.table
// (tableFileName); a model with one is written with writeModelFiles.
// Writes `json` (the model's text) to `file`, the model's measured tables beside it first, each
// atomically.
void writeModelFiles(const std::filesystem::path& file, const Arithmetic& arithmetic,
                     const std::string& json);

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

// A model by name (llvmpipe, softpipe, exact, gl45), a model file, or "auto": the measured model
// of `glRenderer` (measuredModelFile), else gl45. Where a GL context is at hand, "auto" is
// calibrate/fingerprint.h's resolveModelHere, which also confirms a pinned model by probe draws.
PrecisionModel resolveModel(const std::string& nameOrFile, const std::string& glRenderer);

}  // namespace vt
