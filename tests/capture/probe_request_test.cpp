// A triangle probe's request (capture/probe_files.h) keeps how its coordinates are interpolated:
// a noperspective request reads back as one and is another request than the perspective one, a
// perspective request's file names no interpolation (the first pack's files read as before), and
// an interpolation other than noperspective is refused naming the file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "capture/probe_files.h"
#include "common/error.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

capture::ProbeRequest triangle(calibrate::Interpolation interpolation) {
  capture::ProbeRequest r;
  r.kind = capture::ProbeRequest::Kind::kTriangles;
  r.mesh.vertices = {{{-1, -1, 0, 1}, {0, 0}}, {{1, -1, 0, 2}, {1, 0}}, {{0, 1, 0, 4}, {0, 1}}};
  r.mesh.indices = {0, 1, 2};
  r.viewport = {16, 16};
  r.interpolation = interpolation;
  return r;
}

std::string text(const std::filesystem::path& file) {
  std::stringstream s;
  s << std::ifstream(file).rdbuf();
  return s.str();
}

TEST(ProbeRequests, TheInterpolationIsKeptAndOnlyNoperspectiveIsNamed) {
  test::ScratchDirectory dir;
  const capture::ProbeRequest linear = triangle(calibrate::Interpolation::kNoPerspective);
  const capture::ProbeRequest perspective = triangle(calibrate::Interpolation::kPerspective);
  capture::writeProbeRequest(dir.path(), 0, linear);
  capture::writeProbeRequest(dir.path(), 1, perspective);
  const capture::ProbeRequest read = capture::readProbeRequest(dir.path(), 0);
  EXPECT_EQ(read.interpolation, calibrate::Interpolation::kNoPerspective);
  EXPECT_TRUE(capture::sameRequest(read, linear));
  EXPECT_FALSE(capture::sameRequest(read, perspective));
  EXPECT_TRUE(capture::sameRequest(capture::readProbeRequest(dir.path(), 1), perspective));
  EXPECT_THAT(text(dir / "probe-0000.json"), HasSubstr("\"interpolation\": \"noperspective\""));
  EXPECT_THAT(text(dir / "probe-0001.json"), ::testing::Not(HasSubstr("interpolation")));

  std::string flat = text(dir / "probe-0000.json");
  flat.replace(flat.find("noperspective"), 13, "flat");
  std::ofstream(dir / "probe-0000.json", std::ios::trunc) << flat;
  EXPECT_THAT([&] { capture::readProbeRequest(dir.path(), 0); },
              ThrowsMessage<InputError>(AllOf(StartsWith((dir / "probe-0000.json").string()),
                                              HasSubstr("interpolation is not noperspective"))));
}

}  // namespace
}  // namespace vt
