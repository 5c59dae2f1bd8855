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
#include "scene/obj_faces.h"

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
        source_.imageHeader ? source_.imageHeader(image) : readDecodableImageHeader(image);
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
  LibraryReader libraries(source.materialLibraries);
  // Each polygon stays one face; vertex colours are not used.
  const ObjFaces obj = readObjFaces(source.obj, path, &libraries);

  TexturedScene scene;
  scene.name = path.stem().string();
  scene.source = path.string();
  MaterialTextures textures(std::move(folders), imageFolder, obj.materials, source, scene);
  for (const ObjFace& face : obj.faces) {
    if (!face.finite()) {
      ++(face.positions.size() >= 3 ? scene.skipped.notFinite : scene.skipped.degenerate);
      continue;
    }
    const auto corners = static_cast<uint32_t>(face.positions.size());
    const auto base = static_cast<uint32_t>(scene.positions.size());
    scene.faces.push_back({.texture = textures.textureFor(face.material),
                           .firstIndex = static_cast<uint32_t>(scene.indices.size()),
                           .indexCount = 3 * (corners - 2)});
    scene.positions.insert(scene.positions.end(), face.positions.begin(), face.positions.end());
    scene.uvs.insert(scene.uvs.end(), face.uvs.begin(), face.uvs.end());
    fanTriangles(base, corners, scene.indices);
  }
  if (scene.faces.empty()) throw InputError(path, "the mesh has no faces");
  return scene;
}

}  // namespace vt
