#pragma once
// golden.json, a golden set's manifest (golden.h), read and written in one place: what was flown
// (the texture's identity, checksums of the mesh and path files, the configuration, screen size,
// precision profile, every n-th frame) and per recorded frame the checksums of its colour and
// needbuffer with its RMSE, SSIM and WSSIM against the reference image.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "eval/flight_configuration.h"
#include "render/arithmetic.h"
#include "render/frame.h"

namespace vt {

struct GoldenFrame {
  int frame = 0;
  // XXH3-64 in 16 hex digits: of the RGBA8 bytes, rows bottom to top, and of the needbuffer as
  // 32-bit little-endian words.
  std::string color, need;
  double rmse = 0, ssim = 0, wssim = 0;
  std::string image;  // frameNNNN.png beside the manifest
};

struct GoldenManifest {
  std::string texture, textureIdentity;  // the file's name; its identity in 16 hex digits
  std::string mesh, meshChecksum, path, pathChecksum;
  FlightConfiguration configuration;
  Viewport viewport;
  Arithmetic profile;
  int every = 1;
  std::vector<GoldenFrame> frames;

  // The manifest's text (its keys in name order, one space of indentation, a final newline).
  std::string text() const;
  // Every field checked (format, types, ranges, at least one frame); InputError naming `file`.
  static GoldenManifest read(const std::filesystem::path& file);
};

}  // namespace vt
