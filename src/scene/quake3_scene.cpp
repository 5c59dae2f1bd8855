#include "scene/quake3_scene.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>

#include "common/error.h"
#include "common/image_file.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "scene/bsp_entities.h"
#include "scene/missing_texture.h"
#include "scene/quake_axes.h"
#include "scene/texture_resolver.h"

namespace vt {
namespace {

// One surface's triangles in Quake space, indices local to its vertices.
struct SurfaceGeometry {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> st;
  std::vector<uint32_t> indices;
};

std::string mapEntry(std::string_view map) {
  if (map.find('/') != std::string_view::npos) return std::string(map);
  std::string entry = "maps/";
  entry.append(map);
  entry.append(".bsp");
  return entry;
}

// The surface's own vertices (a patch's control points), in Quake space, without triangles.
SurfaceGeometry surfaceVertices(const BspFile& bsp, const BspSurface& surface) {
  SurfaceGeometry geometry;
  for (int32_t v = 0; v < surface.vertexCount; ++v) {
    const BspVertex& vertex = bsp.vertices[static_cast<size_t>(surface.firstVertex + v)];
    geometry.positions.push_back(vertex.position);
    geometry.normals.push_back(vertex.normal);
    geometry.st.push_back(vertex.st);
  }
  return geometry;
}

SurfaceGeometry polygonGeometry(const BspFile& bsp, const BspSurface& surface) {
  SurfaceGeometry geometry = surfaceVertices(bsp, surface);
  for (int32_t i = 0; i < surface.indexCount; ++i)
    geometry.indices.push_back(
        static_cast<uint32_t>(bsp.indices[static_cast<size_t>(surface.firstIndex + i)]));
  return geometry;
}

// Normals are tessellated with the positions' weights, so each vertex has the surface's
// interpolated normal for the winding decision.
SurfaceGeometry patchGeometry(const BspFile& bsp, const BspSurface& surface, int level) {
  const SurfaceGeometry controls = surfaceVertices(bsp, surface);
  TessellatedPatch patch = tessellatePatch(controls.positions, controls.st, surface.patchWidth,
                                           surface.patchHeight, level);
  TessellatedPatch normalPatch = tessellatePatch(controls.normals, controls.st, surface.patchWidth,
                                                 surface.patchHeight, level);
  return {std::move(patch.positions), std::move(normalPatch.positions), std::move(patch.st),
          std::move(patch.indices)};
}

bool isFinite(const SurfaceGeometry& geometry) {
  for (const glm::vec3& p : geometry.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  for (const glm::vec2& st : geometry.st)
    if (!std::isfinite(st.x) || !std::isfinite(st.y)) return false;
  return true;
}

// Winds every triangle counter-clockwise about its vertices' normals; reports whether any
// triangle has a non-zero area.
bool orientTriangles(SurfaceGeometry& geometry) {
  bool anyArea = false;
  for (size_t t = 0; t + 2 < geometry.indices.size(); t += 3) {
    uint32_t* triangle = &geometry.indices[t];
    const glm::vec3 a = geometry.positions[triangle[0]], b = geometry.positions[triangle[1]],
                    c = geometry.positions[triangle[2]];
    const glm::vec3 area = glm::cross(b - a, c - a);
    if (area != glm::vec3(0.0f)) anyArea = true;
    const glm::vec3 normal = geometry.normals[triangle[0]] + geometry.normals[triangle[1]] +
                             geometry.normals[triangle[2]];
    if (glm::dot(area, normal) < 0.0f) std::swap(triangle[1], triangle[2]);
  }
  return anyArea;
}

std::string describeVia(ResolvedTexture::Via via) {
  switch (via) {
    case ResolvedTexture::Via::kImage:
      return "image";
    case ResolvedTexture::Via::kShaderStage:
      return "shader stage";
    case ResolvedTexture::Via::kEditorImage:
      return "shader editor image";
  }
  return "";
}

// Extracts and probes the source images of the map's shaders, once per shader used.
class SourceImages {
 public:
  SourceImages(const PackageFiles& files, const std::filesystem::path& folder)
      : files_(files), resolver_(files), folder_(folder) {}

  uint32_t textureFor(int32_t shader, const std::string& name, TexturedScene& scene) {
    scene_ = &scene;
    if (const auto found = byShader_.find(shader); found != byShader_.end()) return found->second;
    SourceTexture texture;
    texture.name = name;
    if (const auto resolved = resolver_.resolve(name)) extract(*resolved, texture);
    if (texture.file.empty()) {
      useMissingTexture(texture, folder_);
      scene.warnings.push_back("texture " + name + ": no image found, drawn as a checker");
    }
    const auto index = static_cast<uint32_t>(scene.textures.size());
    scene.textures.push_back(std::move(texture));
    byShader_.emplace(shader, index);
    return index;
  }

 private:
  void extract(const ResolvedTexture& resolved, SourceTexture& texture) {
    const std::filesystem::path path =
        pathInside(folder_, resolved.file, files_.describe(resolved.file));
    if (!std::filesystem::exists(path)) {
      const std::vector<uint8_t> bytes = files_.read(resolved.file);
      std::filesystem::create_directories(path.parent_path());
      writeFileAtomically(path, std::as_bytes(std::span(bytes)));
    }
    const std::optional<ImageHeader> header = readDecodableImageHeader(path);
    if (!header || header->width <= 0 || header->height <= 0) {
      scene_->warnings.push_back("texture " + texture.name + ": " + files_.describe(resolved.file) +
                                 " is not a readable image");
      return;
    }
    texture.file = path;
    texture.width = static_cast<uint32_t>(header->width);
    texture.height = static_cast<uint32_t>(header->height);
    texture.foundAs = files_.describe(resolved.file) + " (" + describeVia(resolved.via) + ")";
  }

  const PackageFiles& files_;
  TextureResolver resolver_;
  std::filesystem::path folder_;
  TexturedScene* scene_ = nullptr;  // the scene of the current textureFor call
  std::map<int32_t, uint32_t> byShader_;
};

// The triangles of `indices` grouped by connection (sharing a vertex), each group in its order.
std::vector<std::vector<uint32_t>> connectedPieces(const std::vector<uint32_t>& indices) {
  std::map<uint32_t, uint32_t> parent;
  const auto root = [&](uint32_t v) {
    parent.try_emplace(v, v);
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    for (size_t k = 1; k < 3; ++k) {
      const uint32_t a = root(indices[t]), b = root(indices[t + k]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  std::map<uint32_t, size_t> pieceOf;  // root -> piece, in order of first triangle
  std::vector<std::vector<uint32_t>> pieces;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const auto [found, inserted] = pieceOf.try_emplace(root(indices[t]), pieces.size());
    if (inserted) pieces.emplace_back();
    pieces[found->second].insert(pieces[found->second].end(), indices.begin() + t,
                                 indices.begin() + t + 3);
  }
  return pieces;
}

// Appends the triangles `indices` of `geometry` as one face with vertices of its own.
void addFace(TexturedScene& scene, const SurfaceGeometry& geometry,
             std::span<const uint32_t> indices, uint32_t texture) {
  TexturedFace face{.texture = texture,
                    .firstIndex = static_cast<uint32_t>(scene.indices.size()),
                    .indexCount = static_cast<uint32_t>(indices.size())};
  std::map<uint32_t, uint32_t> vertexOf;  // geometry's vertex -> the scene's
  for (const uint32_t index : indices) {
    auto [found, inserted] =
        vertexOf.try_emplace(index, static_cast<uint32_t>(scene.positions.size()));
    if (inserted) {
      scene.positions.push_back(fromQuake(geometry.positions[index]));
      scene.uvs.push_back(geometry.st[index]);
    }
    scene.indices.push_back(found->second);
  }
  scene.faces.push_back(face);
}

bool skipByShader(const BspShader& shader, SkippedFaces& skipped) {
  if (shader.surfaceFlags & kSurfaceSky) return ++skipped.sky, true;
  if (shader.surfaceFlags & kSurfaceNoDraw) return ++skipped.noDraw, true;
  if (shader.contentFlags & kContentsFog) return ++skipped.fog, true;
  return false;
}

std::vector<Camera> spawnCameras(const std::vector<BspEntity>& entities) {
  std::vector<Camera> cameras;
  for (const char* classname : {"info_player_deathmatch", "info_player_start", "team_CTF_redplayer",
                                "team_CTF_blueplayer", "team_CTF_redspawn", "team_CTF_bluespawn"}) {
    for (const BspEntity& entity : entities) {
      const auto kind = entity.find("classname");
      const auto origin = entity.find("origin");
      if (kind == entity.end() || kind->second != classname || origin == entity.end()) continue;
      glm::vec3 position(NAN);
      std::istringstream(origin->second) >> position.x >> position.y >> position.z;
      float angle = 0.0f;
      if (const auto found = entity.find("angle"); found != entity.end())
        std::istringstream(found->second) >> angle;
      if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z) ||
          !std::isfinite(angle))
        continue;
      const float yaw = glm::radians(angle);
      Camera camera;
      camera.position = fromQuake(position + glm::vec3(0.0f, 0.0f, kQuakeViewHeight));
      camera.target =
          camera.position + directionFromQuake(glm::vec3(std::cos(yaw), std::sin(yaw), 0.0f));
      camera.fovYDegrees = 73.74f;  // Quake 3's 90 degrees horizontally, at 4:3
      cameras.push_back(camera);
    }
    if (!cameras.empty()) break;
  }
  return cameras;
}

bool isDrawnType(BspSurfaceType type) {
  return type == BspSurfaceType::kPolygon || type == BspSurfaceType::kMesh ||
         type == BspSurfaceType::kPatch;
}

bool isDrawnShader(const BspShader& shader) {
  SkippedFaces ignored;
  return !skipByShader(shader, ignored);
}

// Refuses a map whose drawn surfaces would give more vertices or indices than the limits, before
// any is made: surfaces may share vertex ranges, and each patch multiplies its control points.
void requireWithinLimits(const BspFile& bsp, const std::string& source, int patchLevel) {
  // Each term is below 2^42 (parseBsp bounds the counts); the sums saturate rather than wrap.
  const auto add = [](uint64_t& sum, uint64_t term) {
    sum = term > UINT64_MAX - sum ? UINT64_MAX : sum + term;
  };
  uint64_t vertices = 0, indices = 0;
  for (const BspSurface& surface : bsp.surfaces) {
    const auto type = static_cast<BspSurfaceType>(surface.type);
    if (!isDrawnType(type) || !isDrawnShader(bsp.shaders[static_cast<size_t>(surface.shader)]))
      continue;
    if (type == BspSurfaceType::kPatch) {
      // bezier_patch.h: (n * level + 1) x (m * level + 1) vertices, two triangles per cell.
      const uint64_t level = static_cast<uint64_t>(patchLevel);
      const uint64_t columns = static_cast<uint64_t>(surface.patchWidth - 1) / 2 * level,
                     rows = static_cast<uint64_t>(surface.patchHeight - 1) / 2 * level;
      add(vertices, (columns + 1) * (rows + 1));
      add(indices, 6 * columns * rows);
    } else {
      add(vertices, static_cast<uint64_t>(surface.vertexCount));
      add(indices, static_cast<uint64_t>(surface.indexCount));
    }
  }
  const std::string what =
      "tessellating the drawn surfaces (patches at level " + std::to_string(patchLevel) + ")";
  if (vertices > kMaxMapVertices)
    throw limitError(source, what, vertices, kMaxMapVertices, " vertices");
  if (indices > kMaxMapIndices) throw limitError(source, what, indices, kMaxMapIndices, " indices");
}

}  // namespace

std::string quake3MapName(const PackageFiles& files, std::string_view map) {
  const std::string wanted = mapEntry(map);
  const std::optional<std::string> entry = files.find(wanted);
  if (!entry) throw InputError(wanted, "no such map in the packages");
  return std::filesystem::path(*entry).stem().string();
}

TexturedScene loadQuake3Map(const PackageFiles& files, std::string_view map,
                            const std::filesystem::path& imageFolder,
                            const Quake3Options& options) {
  const std::string wanted = mapEntry(map);
  const std::optional<std::string> entry = files.find(wanted);
  if (!entry) throw InputError(wanted, "no such map in the packages");
  const std::vector<uint8_t> bytes = files.read(*entry);
  const std::string source = files.describe(*entry);
  const BspFile bsp = parseBsp(bytes, source);
  SourceImages images(files, imageFolder);
  TexturedScene scene = quake3Scene(
      bsp, source,
      [&](int32_t shader, const std::string& name, TexturedScene& into) {
        return images.textureFor(shader, name, into);
      },
      options);
  scene.name = std::filesystem::path(*entry).stem().string();
  return scene;
}

TexturedScene quake3Scene(const BspFile& bsp, const std::string& source,
                          const ShaderTextures& textureFor, const Quake3Options& options) {
  requireWithinLimits(bsp, source, options.patchLevel);
  TexturedScene scene;
  scene.source = source;
  for (const BspSurface& surface : bsp.surfaces) {
    const BspShader& shader = bsp.shaders[static_cast<size_t>(surface.shader)];
    const auto type = static_cast<BspSurfaceType>(surface.type);
    if (type == BspSurfaceType::kFlare) {
      ++scene.skipped.flare;
      continue;
    }
    if (!isDrawnType(type)) {
      ++scene.skipped.unknownType;
      continue;
    }
    if (skipByShader(shader, scene.skipped)) continue;
    SurfaceGeometry geometry = type == BspSurfaceType::kPatch
                                   ? patchGeometry(bsp, surface, options.patchLevel)
                                   : polygonGeometry(bsp, surface);
    if (!isFinite(geometry)) {
      ++scene.skipped.notFinite;
      continue;
    }
    if (!orientTriangles(geometry)) {
      ++scene.skipped.degenerate;
      continue;
    }
    if (type == BspSurfaceType::kPatch) ++scene.patchFaces;
    const uint32_t texture = textureFor(surface.shader, shader.name, scene);
    if (type == BspSurfaceType::kPatch) {
      addFace(scene, geometry, geometry.indices, texture);
      continue;
    }
    // The map compiler gathers triangles of one plane or shader from many brushes into one
    // surface: each connected piece is a face of its own.
    const std::vector<std::vector<uint32_t>> pieces = connectedPieces(geometry.indices);
    if (pieces.size() > 1) ++scene.splitSurfaces;
    for (const std::vector<uint32_t>& piece : pieces) addFace(scene, geometry, piece, texture);
  }
  if (scene.faces.empty()) throw InputError(source, "the map draws no faces");
  scene.viewpoints = spawnCameras(parseEntities(bsp.entities, source));
  if (scene.viewpoints.empty()) scene.warnings.push_back("the map has no player spawn point");
  return scene;
}

}  // namespace vt
