#pragma once
// Synthetic Quake 3 data for the tests: IBSP 46 files written from their lumps, and zip archives
// (.pk3) written with libzip.

#include <gtest/gtest.h>
#include <zip.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "scene/bsp_file.h"

namespace vt::test {

// ---------------------------------------------------------------------------------------------
// A writer for synthetic IBSP 46 files: the header, then the 17 lumps in order, each at whatever
// offset the previous ones leave (so most lumps after the entity text sit unaligned).

constexpr int kLumps = 17;
constexpr int kShadersLump = 1, kVerticesLump = 10, kIndicesLump = 11, kSurfacesLump = 13;

inline void appendI32(std::vector<uint8_t>& out, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(u >> (8 * i)));
}
inline void appendF32(std::vector<uint8_t>& out, float v) {
  appendI32(out, std::bit_cast<int32_t>(v));
}
inline void putI32(std::vector<uint8_t>& bytes, size_t at, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<uint8_t>(u >> (8 * i));
}
// Byte positions of a lump's directory entry.
inline size_t lumpOffsetAt(int lump) { return 8 + 8 * static_cast<size_t>(lump); }
inline size_t lumpLengthAt(int lump) { return lumpOffsetAt(lump) + 4; }

// A map vertex; the normal faces +z unless given.
inline BspVertex bspVertex(glm::vec3 position, glm::vec2 st, glm::vec3 normal = {0, 0, 1}) {
  return {position, st, normal};
}

struct BspBuilder {
  std::string entities;
  std::vector<BspShader> shaders;
  std::vector<BspVertex> vertices;
  std::vector<int32_t> indices;
  std::vector<BspSurface> surfaces;

  std::vector<uint8_t> build() const {
    std::vector<uint8_t> lumps[kLumps];
    lumps[0].assign(entities.begin(), entities.end());
    lumps[0].push_back(0);  // q3map2 writes the text's terminating NUL
    for (const BspShader& shader : shaders) {
      std::string name = shader.name;
      name.resize(64, '\0');
      lumps[kShadersLump].insert(lumps[kShadersLump].end(), name.begin(), name.end());
      appendI32(lumps[kShadersLump], shader.surfaceFlags);
      appendI32(lumps[kShadersLump], shader.contentFlags);
    }
    for (const BspVertex& v : vertices) {
      std::vector<uint8_t>& out = lumps[kVerticesLump];
      for (int i = 0; i < 3; ++i) appendF32(out, v.position[i]);
      for (int i = 0; i < 2; ++i) appendF32(out, v.st[i]);
      appendF32(out, 0.25f);  // lightmap coordinates, not read
      appendF32(out, 0.75f);
      for (int i = 0; i < 3; ++i) appendF32(out, v.normal[i]);
      for (uint8_t c : {uint8_t{255}, uint8_t{128}, uint8_t{0}, uint8_t{255}}) out.push_back(c);
    }
    for (const int32_t index : indices) appendI32(lumps[kIndicesLump], index);
    for (const BspSurface& s : surfaces) {
      std::vector<uint8_t>& out = lumps[kSurfacesLump];
      for (const int32_t field : {s.shader, s.fog, s.type, s.firstVertex, s.vertexCount,
                                  s.firstIndex, s.indexCount, 3, 16, 32, 8, 8})
        appendI32(out, field);
      for (int i = 0; i < 3; ++i) appendF32(out, 100.0f + i);  // lightmap origin
      for (int i = 0; i < 6; ++i) appendF32(out, -7.0f);       // lightmap s and t vectors
      for (int i = 0; i < 3; ++i) appendF32(out, s.normal[i]);
      appendI32(out, s.patchWidth);
      appendI32(out, s.patchHeight);
    }
    for (int lump : {2, 3, 4}) lumps[lump].assign(12, 0xcd);  // unused lumps, not read

    std::vector<uint8_t> bytes = {'I', 'B', 'S', 'P'};
    appendI32(bytes, 46);
    bytes.resize(8 + 8 * kLumps);
    for (int lump = 0; lump < kLumps; ++lump) {
      putI32(bytes, lumpOffsetAt(lump), static_cast<int32_t>(bytes.size()));
      putI32(bytes, lumpLengthAt(lump), static_cast<int32_t>(lumps[lump].size()));
      bytes.insert(bytes.end(), lumps[lump].begin(), lumps[lump].end());
    }
    return bytes;
  }
};

// Writes a zip archive holding `entries` (name, contents), deflated; a name ending in '/' is a
// folder entry.
inline void writeZip(const std::filesystem::path& path,
                     const std::vector<std::pair<std::string, std::string>>& entries) {
  int code = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  ASSERT_NE(zip, nullptr) << path;
  for (const auto& [name, contents] : entries) {
    if (name.ends_with('/')) {
      ASSERT_GE(zip_dir_add(zip, name.c_str(), ZIP_FL_ENC_UTF_8), 0) << name;
      continue;
    }
    // The source borrows `contents`, which outlives zip_close below.
    zip_source_t* source = zip_source_buffer(zip, contents.data(), contents.size(), 0);
    ASSERT_NE(source, nullptr);
    const zip_int64_t index = zip_file_add(zip, name.c_str(), source, ZIP_FL_ENC_UTF_8);
    ASSERT_GE(index, 0) << name;
    ASSERT_EQ(zip_set_file_compression(zip, static_cast<zip_uint64_t>(index), ZIP_CM_DEFLATE, 9),
              0);
  }
  ASSERT_EQ(zip_close(zip), 0) << zip_strerror(zip);
}

}  // namespace vt::test
