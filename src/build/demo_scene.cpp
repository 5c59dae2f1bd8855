#include "build/demo_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/image_file.h"

namespace vt {
namespace {

using Color = std::array<uint8_t, 3>;

// A well-mixed 32-bit hash of integer coordinates, for per-brick and per-cell variation.
uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  return h;
}

// Smooth value noise in [0, 1] with cells of `cell` texels.
double valueNoise(double x, double y, uint32_t cell, uint32_t seed) {
  const double fx = x / cell, fy = y / cell;
  const auto ix = static_cast<uint32_t>(fx), iy = static_cast<uint32_t>(fy);
  const double tx = fx - ix, ty = fy - iy;
  const auto corner = [&](uint32_t dx, uint32_t dy) {
    return (hash(ix + dx, iy + dy, seed) & 0xffff) / 65535.0;
  };
  const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  const double top = corner(0, 0) * (1 - sx) + corner(1, 0) * sx;
  const double bottom = corner(0, 1) * (1 - sx) + corner(1, 1) * sx;
  return top * (1 - sy) + bottom * sy;
}

uint8_t toByte(double v) {
  return static_cast<uint8_t>(std::clamp(std::lround(v * 255.0), 0L, 255L));
}

Color mix(Color a, Color b, double t) {
  return {toByte((a[0] * (1 - t) + b[0] * t) / 255.0), toByte((a[1] * (1 - t) + b[1] * t) / 255.0),
          toByte((a[2] * (1 - t) + b[2] * t) / 255.0)};
}

void writeMaterial(const std::filesystem::path& path, uint32_t width, uint32_t height,
                   const std::function<Color(uint32_t, uint32_t)>& texel) {
  std::vector<std::byte> texels(size_t{width} * height * 3);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const Color c = texel(x, y);
      for (size_t k = 0; k < 3; ++k) texels[(size_t{y} * width + x) * 3 + k] = std::byte(c[k]);
    }
  writeImage8(path, width, height, 3, texels);
}

Color bricks(uint32_t x, uint32_t y) {
  const uint32_t row = y / 48, offset = (row % 2) * 56, column = (x + offset) / 112;
  const bool mortar = y % 48 < 4 || (x + offset) % 112 < 4;
  if (mortar) return mix({170, 165, 150}, {120, 118, 110}, valueNoise(x, y, 3, 1));
  const double shade = 0.8 + 0.2 * ((hash(column, row, 2) & 0xff) / 255.0);
  const Color brick = mix({150, 60, 40}, {110, 45, 30}, valueNoise(x, y, 9, 3));
  return {toByte(brick[0] * shade / 255), toByte(brick[1] * shade / 255),
          toByte(brick[2] * shade / 255)};
}

Color planks(uint32_t x, uint32_t y) {
  const uint32_t plank = x / 96;
  const double grain =
      0.5 + 0.5 * std::sin((y + 40.0 * valueNoise(x, y, 48, plank)) * 0.21 + plank);
  const Color wood = mix({120, 80, 45}, {170, 120, 70}, grain);
  return x % 96 < 2 ? Color{60, 40, 25} : wood;
}

Color tiles(uint32_t x, uint32_t y) {
  if (x % 64 < 3 || y % 64 < 3) return {200, 200, 195};
  return ((x / 64 + y / 64) % 2) ? Color{30, 60, 110} : Color{235, 230, 220};
}

Color sky(uint32_t x, uint32_t y) {
  const Color base = mix({90, 140, 220}, {200, 225, 250}, y / 299.0);
  const double cloud = std::max(0.0, valueNoise(x, y, 64, 5) * 1.6 - 0.8);
  return mix(base, {255, 255, 255}, cloud);
}

Color marble(uint32_t x, uint32_t y) {
  const double vein = std::abs(std::sin(x * 0.02 + y * 0.013 + 6.0 * valueNoise(x, y, 80, 7)));
  return mix({60, 60, 65}, {235, 235, 230}, std::pow(vein, 0.3));
}

}  // namespace

std::filesystem::path writeDemoScene(const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  struct Material {
    const char* file;
    uint32_t width, height, x, y;
    Color (*texel)(uint32_t, uint32_t);
  };
  const std::array<Material, 5> materials = {{
      {"bricks.png", 1200, 700, 100, 100, bricks},
      {"planks.png", 900, 900, 1500, 200, planks},
      {"tiles.png", 700, 520, 2600, 1300, tiles},
      {"sky.png", 1800, 300, 300, 2100, sky},
      {"marble.png", 640, 470, 3300, 3500, marble},
  }};
  nlohmann::json layout = {
      {"page_size", 128}, {"border", 4}, {"side", 4096}, {"images", nlohmann::json::array()}};
  for (const Material& m : materials) {
    writeMaterial(folder / m.file, m.width, m.height, m.texel);
    layout["images"].push_back({{"file", m.file}, {"x", m.x}, {"y", m.y}});
  }
  const std::filesystem::path file = folder / "layout.json";
  std::ofstream(file) << layout.dump(2) << '\n';
  return file;
}

}  // namespace vt
