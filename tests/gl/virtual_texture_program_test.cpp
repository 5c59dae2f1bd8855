// The shared shader logic is GLSL too: the driver compiles and links the fragment shader that
// includes it verbatim (on llvmpipe in CI).

#include "gl/virtual_texture_program.h"

#include <gtest/gtest.h>

#include "gl/gl_program.h"
#include "gl/headless_context.h"

namespace vt {
namespace {

TEST(VirtualTextureProgram, SharedLogicCompilesAndLinksAsGlsl) {
  const HeadlessContext context;
  std::unique_ptr<GlProgram> program;
  ASSERT_NO_THROW(program = std::make_unique<GlProgram>(virtualTextureVertexSource(),
                                                        virtualTextureFragmentSource()));
  // The parameters struct reaches the program as uniforms of the shared types.
  EXPECT_GE(program->uniform("uVt.pageSize"), 0);
  EXPECT_GE(program->uniform("uVt.cacheSize"), 0);
}

TEST(VirtualTextureProgram, CompileErrorsCarryTheDriversLog) {
  const HeadlessContext context;
  try {
    GlProgram program(virtualTextureVertexSource(),
                      "#version 450 core\nvoid main() { nonsense; }\n");
    FAIL() << "a broken shader linked";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fragment shader does not compile"), std::string::npos);
  }
}

}  // namespace
}  // namespace vt
