// Layouts and `vt build` inputs that must be refused before anything is written, each with its
// own clear error naming the file.

#include "build/layout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "build/texture_builder.h"
#include "common/error.h"
#include "common/image_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

class LayoutInput : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const auto& [name, width, height] :
         std::vector<std::tuple<std::string, uint32_t, uint32_t>>{{"a.png", 40, 30},
                                                                  {"b.png", 20, 10}}) {
      const std::vector<std::byte> texels(size_t{width} * height * 3, std::byte{100});
      writeImage8(dir_ / name, width, height, 3, texels);
    }
  }
  std::filesystem::path layout(const std::string& text) {
    std::ofstream(dir_ / "layout.json") << text;
    return dir_ / "layout.json";
  }
  std::string error(const std::string& text) {
    try {
      readLayout(layout(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "(accepted)";
  }
  test::ScratchDirectory dir_;
};

TEST_F(LayoutInput, ValidLayoutGetsItsSizesFromTheImages) {
  const Layout l = readLayout(layout(
      R"({"page_size": 16, "border": 2, "images": [{"file": "a.png", "x": 0, "y": 0},
          {"file": "b.png", "x": 40, "y": 0}]})"));
  EXPECT_EQ(l.description.pageSize, 16u);
  EXPECT_EQ(l.description.channels, 3u);
  EXPECT_EQ(l.description.sideTexels(), 64u);  // the smallest 16 * 2^L holding x = 60
  EXPECT_EQ(l.description.levelCount, 3u);
  EXPECT_EQ(l.description.colorSpace, ColorSpace::kSrgb);
  EXPECT_EQ(l.filter, MipFilter::kBox);
  ASSERT_EQ(l.images.size(), 2u);
  EXPECT_EQ(l.images[1].width, 20u);
  EXPECT_EQ(l.images[1].file, dir_ / "b.png");
}

TEST_F(LayoutInput, RegionFieldsDefaultToTheWholeImage) {
  const Layout l = readLayout(layout(
      R"({"images": [{"file": "a.png", "x": 0, "y": 0},
          {"file": "a.png", "x": 40, "y": 0, "width": 300, "source_y": -7},
          {"file": "b.png", "x": 0, "y": 30, "source_x": 3}]})"));
  ASSERT_EQ(l.images.size(), 3u);
  EXPECT_FALSE(l.images[0].region);
  EXPECT_EQ(l.images[0].width, 40u);
  EXPECT_EQ(l.images[0].imageWidth, 40u);
  const Placement& wide = l.images[1];
  EXPECT_TRUE(wide.region);
  EXPECT_EQ(wide.width, 300u);
  EXPECT_EQ(wide.height, 30u);  // the image's
  EXPECT_EQ(wide.imageWidth, 40u);
  EXPECT_EQ(wide.imageHeight, 30u);
  EXPECT_EQ(wide.sourceX, 0);
  EXPECT_EQ(wide.sourceY, -7);
  EXPECT_TRUE(l.images[2].region);
  EXPECT_EQ(l.images[2].width, 20u);
  EXPECT_EQ(l.images[2].sourceX, 3);
  EXPECT_EQ(l.description.sideTexels(), 512u);  // the smallest 128 * 2^L holding x = 340
}

TEST_F(LayoutInput, InvalidRegionFields) {
  const std::string named = (dir_ / "layout.json").string() + ": images[1] field ";
  const auto second = [](const std::string& fields) {
    return R"({"images": [{"file": "a.png", "x": 0, "y": 0},
                          {"file": "b.png", "x": 0, "y": 30, )" +
           fields + "}]}";
  };
  EXPECT_THAT(error(second(R"("width": 0)")),
              HasSubstr(named + "width: 0 is not in [1, 134217728] (the format's widest texture)"));
  EXPECT_THAT(error(second(R"("height": 134217729)")),
              HasSubstr(named + "height: 134217729 is not in [1, 134217728]"));
  EXPECT_THAT(error(second(R"("height": -4)")),
              HasSubstr(named + "height: -4 is not a non-negative integer"));
  EXPECT_THAT(error(second(R"("width": 2.5)")),
              HasSubstr(named + "width: 2.5 is not a non-negative integer"));
  EXPECT_THAT(error(second(R"("source_x": 1099511627777)")),
              HasSubstr(named + "source_x: 1099511627777 is not an integer in [-2^40, 2^40]"));
  EXPECT_THAT(error(second(R"("source_y": -1099511627777)")),
              HasSubstr(named + "source_y: -1099511627777 is not an integer in [-2^40, 2^40]"));
  EXPECT_THAT(error(second(R"("source_y": 0.5)")),
              HasSubstr(named + "source_y: 0.5 is not an integer in [-2^40, 2^40]"));
  EXPECT_THAT(error(second(R"("source_x": "3")")),
              HasSubstr(named + "source_x: \"3\" is not an integer in [-2^40, 2^40]"));
  // The limits themselves are valid.
  EXPECT_EQ(error(second(R"("source_x": -1099511627776, "source_y": 1099511627776)")),
            "(accepted)");
}

TEST_F(LayoutInput, RegionsAreCheckedWithTheirPlacedSize) {
  // b.png is 20 x 10; placed 30 wide it reaches into a.png's columns.
  EXPECT_THAT(
      error(R"({"images": [{"file": "a.png", "x": 50, "y": 0},
                                  {"file": "b.png", "x": 21, "y": 5, "width": 30}]})"),
      HasSubstr("b.png and " + (dir_ / "a.png").string() + " overlap (images[1] and images[0])"));
  EXPECT_EQ(error(R"({"images": [{"file": "a.png", "x": 50, "y": 0},
                                {"file": "b.png", "x": 20, "y": 5, "width": 30}]})"),
            "(accepted)");
  EXPECT_THAT(error(R"({"page_size": 16, "side": 64,
                        "images": [{"file": "b.png", "x": 0, "y": 0, "height": 65}]})"),
              HasSubstr("(20 x 65 at 0, 0) reaches outside the texture of 64 x 64 texels "
                        "(images[0])"));
  // Positions near 2^64 do not wrap around.
  EXPECT_THAT(error(R"({"images": [{"file": "b.png", "x": 18446744073709551610, "y": 0}]})"),
              HasSubstr("the texture would be 18446744073709551615 texels wide"));
}

TEST_F(LayoutInput, OverlapsAmongManyPlacements) {
  // A grid of 60 x 60 placements of the same image, then one more overlapping a single one of them.
  std::string images;
  for (int j = 0; j < 60; ++j)
    for (int i = 0; i < 60; ++i)
      images += R"({"file": "b.png", "x": )" + std::to_string(i * 20) + R"(, "y": )" +
                std::to_string(j * 10) + "},";
  EXPECT_EQ(error(R"({"images": [)" + images.substr(0, images.size() - 1) + "]}"), "(accepted)");
  EXPECT_THAT(
      error(R"({"images": [)" + images + R"({"file": "a.png", "x": 1195, "y": 595, "width": 1}]})"),
      HasSubstr("b.png and " + (dir_ / "a.png").string() + " overlap"));
  EXPECT_EQ(error(R"({"images": [)" + images +
                  R"({"file": "a.png", "x": 1200, "y": 0, "height": 600}]})"),
            "(accepted)");
}

TEST_F(LayoutInput, OverlappingPlacements) {
  EXPECT_THAT(error(R"({"images": [{"file": "a.png", "x": 0, "y": 0},
                                  {"file": "b.png", "x": 39, "y": 29}]})"),
              HasSubstr("a.png and " + (dir_ / "b.png").string() + " overlap"));
  // Touching edges do not overlap.
  EXPECT_EQ(error(R"({"images": [{"file": "a.png", "x": 0, "y": 0},
                                {"file": "b.png", "x": 40, "y": 30}]})"),
            "(accepted)");
}

TEST_F(LayoutInput, ImageOutsideTheTexture) {
  EXPECT_THAT(error(R"({"page_size": 16, "side": 64,
                        "images": [{"file": "a.png", "x": 30, "y": 0}]})"),
              HasSubstr("(40 x 30 at 30, 0) reaches outside the texture of 64 x 64 texels"));
}

TEST_F(LayoutInput, MissingOrUnreadableImage) {
  EXPECT_THAT(error(R"({"images": [{"file": "nope.png", "x": 0, "y": 0}]})"),
              HasSubstr("nope.png: image not found (named by " + (dir_ / "layout.json").string() +
                        " images[0])"));
  std::ofstream(dir_ / "junk.png") << "this is not a PNG";
  EXPECT_THAT(error(R"({"images": [{"file": "junk.png", "x": 0, "y": 0}]})"),
              HasSubstr("junk.png: cannot read image"));
}

TEST_F(LayoutInput, PageSizeAndLimits) {
  EXPECT_THAT(error(R"({"page_size": 100, "images": [{"file": "a.png", "x": 0, "y": 0}]})"),
              HasSubstr("field page_size: 100 is not a power of two"));
  EXPECT_THAT(error(R"({"page_size": 16, "border": 16,
                        "images": [{"file": "a.png", "x": 0, "y": 0}]})"),
              HasSubstr("field border: 16 is not smaller than the page size 16"));
  EXPECT_THAT(error(R"({"page_size": 16, "side": 100,
                        "images": [{"file": "a.png", "x": 0, "y": 0}]})"),
              HasSubstr("field side: 100 is not the page size 16 times a power of two"));
  EXPECT_THAT(error(R"({"page_size": 16, "images": [{"file": "a.png", "x": 600000, "y": 0}]})"),
              HasSubstr("the texture would be 600040 texels wide, beyond the format's limit of "
                        "524288 (page size 16 times 2^15)"));
  EXPECT_THAT(error(R"({"channels": 5, "images": [{"file": "a.png", "x": 0, "y": 0}]})"),
              HasSubstr("field channels: 5 is outside [1, 4]"));
}

TEST_F(LayoutInput, MalformedLayoutFiles) {
  EXPECT_THAT(error("{"), HasSubstr("layout.json: not valid JSON"));
  EXPECT_THAT(error("[]"), HasSubstr("the layout is not a JSON object"));
  EXPECT_THAT(error(R"({"images": []})"), HasSubstr("the layout places no images"));
  EXPECT_THAT(error(R"({"images": [{"file": "a.png", "x": -3, "y": 0}]})"),
              HasSubstr("images[0] field x: -3 is not a non-negative integer"));
  EXPECT_THAT(error(R"({"images": [{"x": 0, "y": 0}]})"),
              HasSubstr("images[0] is not an object with file, x and y"));
  EXPECT_THAT(error(R"({"filter": "lanczos", "images": [{"file": "a.png", "x": 0, "y": 0}]})"),
              HasSubstr("filter: 'lanczos' is not one of box, tent"));
  EXPECT_THAT(error(R"({"color_space": 3, "images": [{"file": "a.png", "x": 0, "y": 0}]})"),
              HasSubstr("unexpected value"));
  EXPECT_THAT([&] { readLayout(dir_ / "missing.json"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("cannot open layout file")));
}

TEST_F(LayoutInput, NotEnoughDiskSpaceWritesNothing) {
  const Layout l = readLayout(layout(R"({"images": [{"file": "a.png", "x": 0, "y": 0}]})"));
  const auto output = dir_ / "out.vt";
  EXPECT_THAT(
      [&] {
        buildVirtualTexture(l, output, {.progress = false, .keepFreeBytes = uint64_t{1} << 60});
      },
      ::testing::ThrowsMessage<InputError>(
          HasSubstr("not enough free disk space: the texture needs")));
  EXPECT_FALSE(std::filesystem::exists(output));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_.path()),
                          std::filesystem::directory_iterator()),
            3);  // a.png, b.png, layout.json: no temporary file either
}

}  // namespace
}  // namespace vt
