#pragma once
// The fuzz targets: one entry point per input parser, fed arbitrary bytes. Each file
// tests/fuzz/<name>_fuzz.cpp defines one and, built with VT_LIBFUZZER (scripts/fuzz.sh: clang,
// -fsanitize=fuzzer,address,undefined), becomes the libFuzzer program fuzz_<name>. vt_tests
// compiles the same entry points without libFuzzer and replays every stored input
// (fuzz_regression_test.cpp).
//
// The contract an entry point checks: any input ends in success or in vt::InputError (the error
// the command line prints as one line). Any other exception, a crash, a hang, an allocation
// beyond the fuzzer's limit or a sanitizer report is a bug in the parser.

#include <cstddef>
#include <cstdint>
#include <span>

#include "common/error.h"

namespace vt::fuzz {

using Input = std::span<const uint8_t>;

// A virtual-texture file (format/virtual_texture_reader.h), opened and its first stored pages
// read. Its header, table and page checksums are recomputed first, so that mutations reach the
// fields and the page bytes behind them (the checksum checks have their own tests). Block-
// compressed pages (bc1, bc3) are decoded under each palette rule (format/block_decoding.h), and
// every decoded texel of the first two must lie in the range decodeTexelRange allows.
void virtualTextureFile(Input input);
// A Quake 3 map (scene/bsp_file.h) parsed and made a textured scene (scene/quake3_scene.h), with
// placeholder textures.
void bspMap(Input input);
// A .pk3 archive (scene/package_files.h) in memory: its shader scripts resolved, every file read,
// every map parsed.
void pk3Archive(Input input);
// An OBJ scene with its MTL (scene/obj_scene.h) and the same OBJ as a mesh (scene/obj_mesh.h).
// The text after the line kMtlSeparator is the material library of every `mtllib` line.
void objScene(Input input);
inline constexpr const char* kMtlSeparator = "#vt-fuzz-mtl";
// A layout file of `vt build` (build/layout.h). Images are not opened: a name "WxHxC..." stands
// for an image of W x H texels of C channels, any other name for 64 x 64 x 3, and a name
// starting with "missing" for an image that cannot be read.
void layoutFile(Input input);
// A camera path (scene/camera_path.h), and the camera at a few of its frames.
void cameraPath(Input input);
// Needbuffer readbacks (shader/needbuffer.h, runtime/needbuffer_analysis.h): byte 0 selects the
// encoding and statistics, bytes 1-2 the width, the rest are RGBA32UI pixels.
void needBuffer(Input input);

// A capture manifest (<vt/oracle/capture.h>) next to fixed data files (capture_fuzz.cpp), read,
// drawn and compared by the oracle.
void captureManifest(Input input);

// A precision-model file (render/precision_model_file.h), and, when it reads, the file modelJson
// writes of it read back to the same modelJson: a model survives being written.
void precisionModel(Input input);
// A calibration probe folder (capture/probe_files.h) as `vt calibrate --probes` and `vt-capture
// probes` read it: probes.json, the request probe-0000.json, its data files and its result. The
// text before the first kProbeFileSeparator line is probe-0000.json; each such line names the
// file the bytes after it are written to ("probes.json", or the part of a data file's name after
// "probe-0000.": "inputs.f32", "result", ...). A request that reads must be written and read back
// the same, and its result written back byte for byte.
void probeFolder(Input input);
inline constexpr const char* kProbeFileSeparator = "#vt-fuzz-file ";
// A configurations file of `vt eval --configs` (eval/configurations_file.h), the same text as one
// configuration of `--config` (eval/flight_configuration.h), and each configuration that reads
// written (toJson) and read back the same.
void configurationFile(Input input);

// A shard's record (shard.json of `--shard I/N`, common/shard.h) as `vt merge` reads it, and the
// records of a crosscheck's shard decoded, written and read back the same.
void shardRecord(Input input);

struct Target {
  const char* name;  // the folder of its regression inputs and the program fuzz_<name>
  void (*run)(Input);
};

inline constexpr Target kTargets[] = {
    {"vt_file", &virtualTextureFile},
    {"bsp", &bspMap},
    {"pk3", &pk3Archive},
    {"obj", &objScene},
    {"layout", &layoutFile},
    {"camera_path", &cameraPath},
    {"needbuffer", &needBuffer},
    {"capture", &captureManifest},
    {"precision_model", &precisionModel},
    {"probe_folder", &probeFolder},
    {"config", &configurationFile},
    {"shard", &shardRecord},
};

}  // namespace vt::fuzz

// Defines libFuzzer's entry point for `function` in the fuzz programs; nothing in vt_tests.
#ifdef VT_LIBFUZZER
#define VT_FUZZ_TARGET(function)                                              \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {   \
    try {                                                                     \
      function(vt::fuzz::Input(data, size));                                  \
    } catch (const vt::InputError&) {                                         \
      /* a clean rejection; anything else escapes and libFuzzer reports it */ \
    }                                                                         \
    return 0;                                                                 \
  }
#else
#define VT_FUZZ_TARGET(function)
#endif
