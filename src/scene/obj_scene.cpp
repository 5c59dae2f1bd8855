#include "scene/obj_scene.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "common/error.h"
#include "common/image_file.h"
#include "common/input_file.h"
#include "scene/missing_texture.h"

namespace vt {
namespace {

// The folder of the MTL file defining each material (map_Kd names are relative to it). A library
// the OBJ names but the source lacks is an error (tinyobjloader only warns).
std::map<std::string, std::filesystem::path> materialFolders(const ObjSceneText& source) {
  std::map<std::string, std::filesystem::path> folders;
  for (const std::string& library : materialLibraryNames(source.obj)) {
    const auto text = source.materialLibraries.find(library);
    if (text == source.materialLibraries.end())
      throw InputError(source.path, "material library " + library + " not found");
    const std::filesystem::path folder = (source.path.parent_path() / library).parent_path();
    std::istringstream mtl(text->second);
    std::string definition;
    while (std::getline(mtl, definition)) {
      std::istringstream parts(definition);
      std::string word, name;
      if (parts >> word >> name && word == "newmtl") folders.try_emplace(name, folder);
    }
  }
  return folders;
}

// Serves tinyobjloader the material libraries of an ObjSceneText by name.
class LibraryReader : public tinyobj::MaterialReader {
 public:
  explicit LibraryReader(const std::map<std::string, std::string>& libraries)
      : libraries_(libraries) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* materialIds, std::string* warning,
                  std::string* error) override {
    const auto text = libraries_.find(name);
    if (text == libraries_.end()) return false;
    std::istringstream stream(text->second);
    tinyobj::LoadMtl(materialIds, materials, &stream, warning, error);
    return true;
  }

 private:
  const std::map<std::string, std::string>& libraries_;
};

class MaterialTextures {
 public:
  MaterialTextures(std::map<std::string, std::filesystem::path> folders,
                   const std::filesystem::path& imageFolder,
                   const std::vector<tinyobj::material_t>& materials, const ObjSceneText& source,
                   TexturedScene& scene)
      : folders_(std::move(folders)),
        imageFolder_(imageFolder),
        materials_(materials),
        source_(source),
        scene_(scene) {}

  uint32_t textureFor(int material) {
    if (const auto found = byMaterial_.find(material); found != byMaterial_.end())
      return found->second;
    SourceTexture texture;
    if (material >= 0 && static_cast<size_t>(material) < materials_.size()) {
      const tinyobj::material_t& m = materials_[static_cast<size_t>(material)];
      texture.name = m.name;
      if (!m.diffuse_texname.empty())
        probe(folders_[m.name] / m.diffuse_texname, texture);
      else
        scene_.warnings.push_back("material " + m.name + ": no map_Kd, drawn as a checker");
    } else {
      texture.name = "(no material)";
      scene_.warnings.push_back("faces without a material are drawn as a checker");
    }
    if (texture.file.empty()) useMissingTexture(texture, imageFolder_);
    const auto index = static_cast<uint32_t>(scene_.textures.size());
    scene_.textures.push_back(std::move(texture));
    byMaterial_.emplace(material, index);
    return index;
  }

 private:
  void probe(const std::filesystem::path& image, SourceTexture& texture) {
    const std::optional<ImageHeader> header =
        source_.imageHeader ? source_.imageHeader(image) : readImageHeader(image);
    if (!header || header->width <= 0 || header->height <= 0) {
      scene_.warnings.push_back("material " + texture.name + ": " + image.string() +
                                " is not a readable image, drawn as a checker");
      return;
    }
    texture.file = std::filesystem::absolute(image);
    texture.width = static_cast<uint32_t>(header->width);
    texture.height = static_cast<uint32_t>(header->height);
    texture.foundAs = image.string();
  }

  std::map<std::string, std::filesystem::path> folders_;  // material name -> its MTL's folder
  std::filesystem::path imageFolder_;
  const std::vector<tinyobj::material_t>& materials_;
  const ObjSceneText& source_;
  TexturedScene& scene_;
  std::map<int, uint32_t> byMaterial_;
};

}  // namespace

std::vector<std::string> materialLibraryNames(std::string_view objText) {
  std::vector<std::string> names;
  std::istringstream lines{std::string(objText)};
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string keyword, library;
    words >> keyword;
    if (keyword != "mtllib") continue;
    while (words >> library) names.push_back(library);
  }
  return names;
}

TexturedScene loadObjScene(const std::filesystem::path& path,
                           const std::filesystem::path& imageFolder) {
  if (!std::filesystem::exists(path)) throw InputError(path, "mesh not found");
  ObjSceneText source{path, readTextFile(path, "mesh"), {}};
  for (const std::string& library : materialLibraryNames(source.obj)) {
    const std::filesystem::path file = path.parent_path() / library;
    if (!std::filesystem::exists(file))
      throw InputError(path, "material library " + library + " not found");
    source.materialLibraries.try_emplace(library, readTextFile(file, "material library"));
  }
  return loadObjScene(source, imageFolder);
}

TexturedScene loadObjScene(const ObjSceneText& source, const std::filesystem::path& imageFolder) {
  const std::filesystem::path& path = source.path;
  std::map<std::string, std::filesystem::path> folders = materialFolders(source);
  tinyobj::attrib_t attributes;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  std::istringstream obj(source.obj);
  LibraryReader libraries(source.materialLibraries);
  // Each polygon stays one face (no triangulation); vertex colours are not used.
  if (!tinyobj::LoadObj(&attributes, &shapes, &materials, &warning, &error, &obj, &libraries,
                        /*triangulate=*/false, /*default_vcols_fallback=*/true))
    throw InputError(path, "cannot read OBJ: " + error);

  TexturedScene scene;
  scene.name = path.stem().string();
  MaterialTextures textures(std::move(folders), imageFolder, materials, source, scene);
  for (const auto& shape : shapes) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const size_t corners = shape.mesh.num_face_vertices[f];
      std::vector<glm::vec3> positions;
      std::vector<glm::vec2> uvs;
      for (size_t c = 0; c < corners; ++c) {
        const tinyobj::index_t& index = shape.mesh.indices[offset + c];
        if (index.texcoord_index < 0)
          throw InputError(path,
                           "shape '" + shape.name + "' has a face without texture coordinates");
        const auto v = static_cast<size_t>(index.vertex_index),
                   t = static_cast<size_t>(index.texcoord_index);
        if (index.vertex_index < 0 || 3 * v + 2 >= attributes.vertices.size() ||
            2 * t + 1 >= attributes.texcoords.size())
          throw InputError(path, "shape '" + shape.name + "' has an index out of range");
        positions.emplace_back(attributes.vertices[3 * v], attributes.vertices[3 * v + 1],
                               attributes.vertices[3 * v + 2]);
        uvs.emplace_back(attributes.texcoords[2 * t], 1.0f - attributes.texcoords[2 * t + 1]);
      }
      offset += corners;
      bool finite = corners >= 3;
      for (size_t c = 0; c < corners; ++c)
        finite = finite && std::isfinite(positions[c].x) && std::isfinite(positions[c].y) &&
                 std::isfinite(positions[c].z) && std::isfinite(uvs[c].x) &&
                 std::isfinite(uvs[c].y);
      if (!finite) {
        ++(corners >= 3 ? scene.skipped.notFinite : scene.skipped.degenerate);
        continue;
      }
      const int material = shape.mesh.material_ids.empty() ? -1 : shape.mesh.material_ids[f];
      const auto base = static_cast<uint32_t>(scene.positions.size());
      TexturedFace face{.texture = textures.textureFor(material),
                        .firstIndex = static_cast<uint32_t>(scene.indices.size()),
                        .indexCount = static_cast<uint32_t>(3 * (corners - 2))};
      scene.positions.insert(scene.positions.end(), positions.begin(), positions.end());
      scene.uvs.insert(scene.uvs.end(), uvs.begin(), uvs.end());
      for (uint32_t c = 1; c + 1 < corners; ++c)
        scene.indices.insert(scene.indices.end(), {base, base + c, base + c + 1});
      scene.faces.push_back(face);
    }
  }
  if (scene.faces.empty()) throw InputError(path, "the mesh has no faces");
  return scene;
}

}  // namespace vt
