#pragma once
// A scene as a conventional renderer draws it, the input of retexturing (thesis 3.3.2): faces of
// triangles, each face textured by one source image through texture coordinates that repeat
// outside [0, 1]. World convention as in mesh.h: right-handed, y up.

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/camera.h"

namespace vt {

struct SourceTexture {
  std::string name;            // as the scene names it
  std::filesystem::path file;  // the image on disk (a checker image when the source's is missing)
  uint32_t width = 0, height = 0;
  bool missing = false;  // no image was found: `file` is the checker
  std::string foundAs;   // where the image came from, e.g. "pak0.pk3:textures/x.tga (shader stage)"
};

struct TexturedFace {
  uint32_t texture = 0;                     // index into TexturedScene::textures
  uint32_t firstIndex = 0, indexCount = 0;  // its triangles in TexturedScene::indices
};

// Faces of the source that are not drawn with a texture, counted by why they were skipped.
struct SkippedFaces {
  uint32_t flare = 0;   // billboards and flares
  uint32_t sky = 0;     // sky shaders
  uint32_t noDraw = 0;  // nodraw shaders
  uint32_t fog = 0;     // fog volumes
  uint32_t unknownType = 0;
  uint32_t notFinite = 0;   // a vertex position or texture coordinate is NaN or infinite
  uint32_t degenerate = 0;  // no triangle of non-zero area
  uint32_t total() const {
    return flare + sky + noDraw + fog + unknownType + notFinite + degenerate;
  }
};

// Vertices are not shared between faces: each face owns the vertices its indices name.
struct TexturedScene {
  std::string name;
  // The file it was read from ("maps/q3dm6.bsp", "pak0.pk3: maps/q3dm6.bsp", "scene.obj"): what
  // every refusal about its contents names. Empty for a scene made in memory.
  std::string source;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;     // source coordinates (s, t), t along the image's rows
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from the front
  std::vector<TexturedFace> faces;
  std::vector<SourceTexture> textures;
  SkippedFaces skipped;
  uint32_t patchFaces = 0;            // faces tessellated from curved patches
  uint32_t splitSurfaces = 0;         // surfaces of several unconnected pieces, one face per piece
  std::vector<Camera> viewpoints;     // where players start (Quake 3 spawn points), in entity order
  std::vector<std::string> warnings;  // one line each, e.g. a texture that was not found
};

// What a refusal about the scene's contents names: its file, or its name for a scene made in
// memory.
inline const std::string& describedSource(const TexturedScene& scene) {
  return scene.source.empty() ? scene.name : scene.source;
}

}  // namespace vt
