#pragma once
// A Quake 3 map file (IBSP version 46) parsed into the lumps a renderer needs: the entity text,
// the shader references, the draw vertices and indices, and the surfaces. Coordinates stay in
// Quake's units and axes (scene/quake_axes.h converts them).
//
// Every count and offset is checked against the file before it is used: a truncated file, a lump
// past the end, a lump whose size is not a whole number of records, a surface whose vertex or
// index range leaves its lump, an index outside its surface's vertices, a shader number out of
// range or a patch whose control grid is not (2n+1) x (2m+1) with w * h vertices is an InputError
// naming the map and the lump or surface. Polygon and mesh surfaces whose index counts add up to
// more than kMaxMapIndices (common/resource_limits.h) are refused before any index is checked.

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

namespace vt {

struct BspShader {
  std::string name;  // e.g. "textures/base_wall/concrete", no extension
  int32_t surfaceFlags = 0;
  int32_t contentFlags = 0;
};

// Flags of BspShader that decide whether a surface is drawn (Quake 3's surfaceflags.h).
inline constexpr int32_t kSurfaceSky = 0x4;
inline constexpr int32_t kSurfaceNoDraw = 0x80;
inline constexpr int32_t kContentsFog = 0x40;

struct BspVertex {
  glm::vec3 position{0.0f};
  glm::vec2 st{0.0f};  // texture coordinates of the source texture, repeating outside [0, 1]
  glm::vec3 normal{0.0f};
};

enum class BspSurfaceType : int32_t { kPolygon = 1, kPatch = 2, kMesh = 3, kFlare = 4 };

struct BspSurface {
  int32_t shader = 0;
  int32_t fog = -1;
  int32_t type = 0;  // a BspSurfaceType value; other values are kept so the scene can count them
  int32_t firstVertex = 0, vertexCount = 0;
  int32_t firstIndex = 0, indexCount = 0;   // indices are relative to firstVertex
  glm::vec3 normal{0.0f};                   // the plane normal of polygon surfaces
  int32_t patchWidth = 0, patchHeight = 0;  // control points of patch surfaces
};

struct BspFile {
  std::string entities;  // the entity lump's text
  std::vector<BspShader> shaders;
  std::vector<BspVertex> vertices;
  std::vector<int32_t> indices;
  std::vector<BspSurface> surfaces;
};

// Parses and validates a map held in memory; `name` (e.g. "pak1-maps.pk3:maps/q3dm6ish.bsp")
// names it in errors.
BspFile parseBsp(std::span<const uint8_t> bytes, const std::string& name);

}  // namespace vt
