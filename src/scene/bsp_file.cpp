#include "scene/bsp_file.h"

#include <algorithm>
#include <cstddef>
#include <string_view>

#include "common/error.h"
#include "common/little_endian.h"
#include "common/resource_limits.h"

namespace vt {
namespace {

// The header: "IBSP", int32 version, then 17 lump directory entries of (int32 offset, int32
// length), all little-endian (Quake 3's qfiles.h).
constexpr int32_t kBspVersion = 46;
constexpr int kLumpCount = 17;
constexpr size_t kHeaderSize = 8 + 8 * kLumpCount;

constexpr std::string_view kLumpNames[kLumpCount] = {
    "entities",    "shaders",  "planes",    "nodes",      "leafs",     "leafsurfaces",
    "leafbrushes", "models",   "brushes",   "brushsides", "drawverts", "drawindexes",
    "fogs",        "surfaces", "lightmaps", "lightgrid",  "visibility"};

constexpr int kEntitiesLump = 0;
constexpr int kShadersLump = 1;
constexpr int kVerticesLump = 10;
constexpr int kIndicesLump = 11;
constexpr int kSurfacesLump = 13;

// Record sizes of the lumps read here: dshader_t, drawVert_t, int, dsurface_t.
constexpr size_t kShaderSize = 72;
constexpr size_t kVertexSize = 44;
constexpr size_t kIndexSize = 4;
constexpr size_t kSurfaceSize = 104;
constexpr size_t kShaderNameSize = 64;

// The file's bytes may sit at any alignment: every field is assembled byte by byte.
int32_t loadI32(const uint8_t* p) {
  return static_cast<int32_t>(loadU32(reinterpret_cast<const std::byte*>(p)));
}
float loadFloat(const uint8_t* p) { return loadF32(reinterpret_cast<const std::byte*>(p)); }
glm::vec2 loadVec2(const uint8_t* p) { return {loadFloat(p), loadFloat(p + 4)}; }
glm::vec3 loadVec3(const uint8_t* p) { return {loadFloat(p), loadFloat(p + 4), loadFloat(p + 8)}; }

std::string lumpLabel(int lump) { return "lump " + std::string(kLumpNames[lump]); }

// Shows four magic bytes as text, with anything unprintable as a hex escape.
std::string describeMagic(std::span<const uint8_t> magic) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string text;
  for (const uint8_t c : magic) {
    if (c >= 0x20 && c < 0x7f) {
      text += static_cast<char>(c);
    } else {
      text += "\\x";
      text += kHex[c >> 4];
      text += kHex[c & 15];
    }
  }
  return text;
}

class BspParser {
 public:
  BspParser(std::span<const uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  BspFile parse() {
    checkHeader();
    BspFile bsp;
    bsp.entities = readEntities();
    bsp.shaders = readShaders();
    bsp.vertices = readVertices();
    bsp.indices = readIndices();
    bsp.surfaces = readSurfaces();
    checkIndexTotal(bsp);
    for (size_t s = 0; s < bsp.surfaces.size(); ++s) checkSurface(bsp, s);
    return bsp;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw InputError(name_, where + ": " + problem);
  }

  void checkHeader() const {
    if (bytes_.size() < kHeaderSize)
      fail("header", "truncated: the file has " + std::to_string(bytes_.size()) +
                         " bytes, the header needs " + std::to_string(kHeaderSize));
    const std::span<const uint8_t> magic = bytes_.first(4);
    if (!std::ranges::equal(magic, std::string_view("IBSP")))
      fail("header", "bad magic '" + describeMagic(magic) + "', expected 'IBSP'");
    const int32_t version = loadI32(bytes_.data() + 4);
    if (version != kBspVersion)
      fail("header", "version " + std::to_string(version) + " is not " +
                         std::to_string(kBspVersion) + " (Quake 3)");
  }

  // The bytes of one lump, checked to lie inside the file and to hold whole records. Only the
  // lumps read here are checked: the others are never touched.
  std::span<const uint8_t> lump(int index, size_t recordSize) const {
    const uint8_t* entry = bytes_.data() + 8 + 8 * index;
    const int64_t offset = loadI32(entry), length = loadI32(entry + 4);
    const std::string label = lumpLabel(index);
    if (offset < 0) fail(label, "negative offset " + std::to_string(offset));
    if (length < 0) fail(label, "negative length " + std::to_string(length));
    if (offset + length > static_cast<int64_t>(bytes_.size()))
      fail(label, "offset " + std::to_string(offset) + " + length " + std::to_string(length) +
                      " is past the end of the " + std::to_string(bytes_.size()) + "-byte file");
    if (length % static_cast<int64_t>(recordSize) != 0)
      fail(label, "length " + std::to_string(length) + " is not a multiple of the " +
                      std::to_string(recordSize) + "-byte record");
    return bytes_.subspan(static_cast<size_t>(offset), static_cast<size_t>(length));
  }

  // Quake 3 reads the entity text as a C string: it ends at the first NUL (usually the last byte).
  std::string readEntities() const {
    const std::span<const uint8_t> text = lump(kEntitiesLump, 1);
    const auto end = std::ranges::find(text, uint8_t{0});
    return std::string(text.begin(), end);
  }

  std::vector<BspShader> readShaders() const {
    const std::span<const uint8_t> data = lump(kShadersLump, kShaderSize);
    std::vector<BspShader> shaders(data.size() / kShaderSize);
    for (size_t i = 0; i < shaders.size(); ++i) {
      const uint8_t* record = data.data() + i * kShaderSize;
      // The name is NUL-padded; one that fills all 64 bytes has no NUL at all.
      const uint8_t* nameEnd = std::find(record, record + kShaderNameSize, uint8_t{0});
      shaders[i].name.assign(record, nameEnd);
      shaders[i].surfaceFlags = loadI32(record + 64);
      shaders[i].contentFlags = loadI32(record + 68);
    }
    return shaders;
  }

  // drawVert_t: xyz[3], st[2], lightmap[2], normal[3], color[4] bytes.
  std::vector<BspVertex> readVertices() const {
    const std::span<const uint8_t> data = lump(kVerticesLump, kVertexSize);
    std::vector<BspVertex> vertices(data.size() / kVertexSize);
    for (size_t i = 0; i < vertices.size(); ++i) {
      const uint8_t* record = data.data() + i * kVertexSize;
      vertices[i].position = loadVec3(record);
      vertices[i].st = loadVec2(record + 12);
      vertices[i].normal = loadVec3(record + 28);
    }
    return vertices;
  }

  std::vector<int32_t> readIndices() const {
    const std::span<const uint8_t> data = lump(kIndicesLump, kIndexSize);
    std::vector<int32_t> indices(data.size() / kIndexSize);
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = loadI32(data.data() + i * kIndexSize);
    return indices;
  }

  // dsurface_t: 12 int32 (shader, fog, type, firstVert, numVerts, firstIndex, numIndexes,
  // lightmap number, x, y, width, height), lightmapOrigin[3], lightmapVecs[3][3] (the third is
  // the plane normal), patchWidth, patchHeight.
  std::vector<BspSurface> readSurfaces() const {
    const std::span<const uint8_t> data = lump(kSurfacesLump, kSurfaceSize);
    std::vector<BspSurface> surfaces(data.size() / kSurfaceSize);
    for (size_t i = 0; i < surfaces.size(); ++i) {
      const uint8_t* record = data.data() + i * kSurfaceSize;
      BspSurface& surface = surfaces[i];
      surface.shader = loadI32(record);
      surface.fog = loadI32(record + 4);
      surface.type = loadI32(record + 8);
      surface.firstVertex = loadI32(record + 12);
      surface.vertexCount = loadI32(record + 16);
      surface.firstIndex = loadI32(record + 20);
      surface.indexCount = loadI32(record + 24);
      surface.normal = loadVec3(record + 60 + 2 * 12);
      surface.patchWidth = loadI32(record + 96);
      surface.patchHeight = loadI32(record + 100);
    }
    return surfaces;
  }

  // Surfaces may share index ranges: a small file could make every index be checked (and
  // later drawn) billions of times. Refused before any is checked (common/resource_limits.h).
  void checkIndexTotal(const BspFile& bsp) const {
    uint64_t total = 0;
    for (const BspSurface& surface : bsp.surfaces) {
      const auto type = static_cast<BspSurfaceType>(surface.type);
      if ((type == BspSurfaceType::kPolygon || type == BspSurfaceType::kMesh) &&
          surface.indexCount > 0)
        total += static_cast<uint64_t>(surface.indexCount);
    }
    if (total > kMaxMapIndices)
      throw limitError(name_, "the triangle list of the polygon and mesh surfaces", total,
                       kMaxMapIndices, " indices");
  }

  // Checks that [first, first + count) lies inside a lump of `size` records.
  void checkRange(const std::string& where, const char* what, int64_t first, int64_t count,
                  size_t size, const char* lumpName) const {
    if (first < 0 || count < 0 || first + count > static_cast<int64_t>(size))
      fail(where, std::string(what) + " range [" + std::to_string(first) + ", " +
                      std::to_string(first + count) + ") is outside the " + std::to_string(size) +
                      " records of lump " + lumpName);
  }

  void checkSurface(const BspFile& bsp, size_t s) const {
    const BspSurface& surface = bsp.surfaces[s];
    const std::string where = "surface " + std::to_string(s);
    if (surface.shader < 0 || static_cast<size_t>(surface.shader) >= bsp.shaders.size())
      fail(where, "shader number " + std::to_string(surface.shader) + " is outside the " +
                      std::to_string(bsp.shaders.size()) + " shaders");
    const auto type = static_cast<BspSurfaceType>(surface.type);
    const bool drawn = type == BspSurfaceType::kPolygon || type == BspSurfaceType::kPatch ||
                       type == BspSurfaceType::kMesh;
    // Flares and unknown types are skipped by the scene: only vertices they claim are checked.
    if (drawn || surface.vertexCount > 0)
      checkRange(where, "vertex", surface.firstVertex, surface.vertexCount, bsp.vertices.size(),
                 "drawverts");
    if (type == BspSurfaceType::kPolygon || type == BspSurfaceType::kMesh)
      checkTriangles(bsp, surface, where);
    if (type == BspSurfaceType::kPatch) checkPatch(surface, where);
  }

  void checkTriangles(const BspFile& bsp, const BspSurface& surface,
                      const std::string& where) const {
    checkRange(where, "index", surface.firstIndex, surface.indexCount, bsp.indices.size(),
               "drawindexes");
    if (surface.indexCount % 3 != 0)
      fail(where, "index count " + std::to_string(surface.indexCount) + " is not a multiple of 3");
    for (int32_t i = 0; i < surface.indexCount; ++i) {
      const int32_t index = bsp.indices[static_cast<size_t>(surface.firstIndex + i)];
      if (index < 0 || index >= surface.vertexCount)
        fail(where, "index " + std::to_string(index) + " (drawindexes record " +
                        std::to_string(surface.firstIndex + i) + ") is outside the surface's " +
                        std::to_string(surface.vertexCount) + " vertices");
    }
  }

  void checkPatchSide(const std::string& where, const char* side, int32_t size) const {
    if (size < 3 || size % 2 == 0)
      fail(where, std::string("patch ") + side + " " + std::to_string(size) +
                      (size < 3 ? " is less than 3" : " is even") +
                      ": it must be 2n+1 control points");
  }

  // A patch is a grid of (2n+1) x (2m+1) control points: biquadratic patches sharing edges.
  void checkPatch(const BspSurface& surface, const std::string& where) const {
    const int32_t w = surface.patchWidth, h = surface.patchHeight;
    checkPatchSide(where, "width", w);
    checkPatchSide(where, "height", h);
    if (int64_t{w} * h != surface.vertexCount)
      fail(where, "patch size " + std::to_string(w) + " x " + std::to_string(h) +
                      " does not match its " + std::to_string(surface.vertexCount) + " vertices");
  }

  std::span<const uint8_t> bytes_;
  const std::string& name_;
};

}  // namespace

BspFile parseBsp(std::span<const uint8_t> bytes, const std::string& name) {
  return BspParser(bytes, name).parse();
}

}  // namespace vt
