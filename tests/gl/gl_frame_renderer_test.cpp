// The GL path keeps the FrameRenderer contract (render/frame_renderer_contract.h) on whatever
// driver runs the tests: delayed readback through pixel-buffer objects included.

#include "gl/gl_frame_renderer.h"

#include <gtest/gtest.h>

#include "gl/headless_context.h"
#include "render/frame_renderer_contract.h"

namespace vt {
namespace {

std::unique_ptr<FrameRenderer> gl(const CacheState& cache) {
  return std::make_unique<GlFrameRenderer>(cache);
}

TEST(GlFrameRenderer, HandsOutTheNeedbufferAndDepthOneFrameLateUnderDelayedReadback) {
  const HeadlessContext context;
  test::expectDelayedReadbackOneFrameLate(gl, test::ContractScene());
}

TEST(GlFrameRenderer, ReadsBackWhatIsAsked) {
  const HeadlessContext context;
  test::expectReadsBackWhatIsAsked(gl, test::ContractScene());
}

TEST(GlFrameRenderer, DrawsTheChangedCacheStateOnceTold) {
  const HeadlessContext context;
  test::expectDrawsTheChangedCacheState(gl, test::ContractScene());
}

}  // namespace
}  // namespace vt
