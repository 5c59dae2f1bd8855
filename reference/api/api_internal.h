#pragma once
// What the API's implementation shares: the texture behind the public handle, conversions to the
// oracle's internal types, and the one place where internal exceptions become vt::oracle::Error
// (the shared library hides the internal exception types; callers catch Error).

#include <memory>
#include <mutex>
#include <optional>
#include <vector>
#include <span>
#include <utility>

#include "format/virtual_texture_reader.h"
#include "reference/renderer.h"
#include "reference/texture_source.h"
#include "render/cache_state.h"
#include "render/frame.h"
#include "vt/oracle/error.h"
#include "vt/oracle/render.h"
#include "vt/oracle/texture.h"

namespace vt::oracle {

struct Texture::Impl {
  explicit Impl(const std::filesystem::path& path) : reader(path), everything(reader) {}
  VirtualTextureReader reader;
  reference::ResidentTexture everything;  // pages decoded on first use, kept
};

struct PreparedCache::Impl {
  Impl(const Texture::Impl& t, std::optional<vt::CacheState> s)
      : texture(t), state(std::move(s)) {}

  const Texture::Impl& texture;
  std::optional<vt::CacheState> state;  // none: every page resident
  // A block format's state decoded again for each other decoding a render asked for, kept.
  mutable std::mutex decodedMutex;
  mutable std::vector<std::unique_ptr<const vt::CacheState>> decoded;

  // The state as the oracle samples it under `decoding`.
  const vt::CacheState& stateFor(vt::BlockDecoding decoding) const {
    if (!decodesDifferently(*state, decoding)) return *state;
    const std::lock_guard lock(decodedMutex);
    for (const auto& d : decoded)
      if (d->decoding == decoding) return *d;
    decoded.push_back(std::make_unique<const vt::CacheState>(withDecoding(*state, decoding)));
    return *decoded.back();
  }
};

// Runs `work`, turning every exception but Error into Error with the same message.
template <class Work>
auto translatingErrors(Work&& work) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}

// The result sets behind the public handle.
struct ResultSets {
  vt::ResultSets sets;
};

// A frame's result sets as the oracle's type, read where they are: empty (a pinned model's, whose
// frames carry none) when the frame has none.
inline const vt::ResultSets& internalSets(const Frame& frame) {
  static const vt::ResultSets kNone;
  return frame.sets ? frame.sets->sets : kNone;
}

vt::PrecisionModel internalModel(Profile profile);
Profile publicProfile(const vt::PrecisionModel& model);
vt::RenderSettings internalSettings(Viewport viewport, const RenderOptions& options);
ClipSpaceMesh internalMesh(const Scene& scene);
vt::CacheState internalCache(const VirtualTextureReader& reader, const CacheState& cache);
Frame publicFrame(vt::Frame&& frame, const vt::RenderSettings& settings);
// A clip-space mesh as the API's scene, and a needbuffer as four values per pixel: the
// conversions the implementation and the command line share.
Scene publicScene(const ClipSpaceMesh& mesh, vt::Viewport viewport);
std::vector<uint32_t> flatNeed(std::span<const glm::uvec4> need);

}  // namespace vt::oracle
