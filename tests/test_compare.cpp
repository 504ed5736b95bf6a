// `sluice compare` as a CI script sees it (docs/cli.md, "compare"): every exit status
// (0 same, 1 different, 2 usage, 3 unreadable, 4 sizes differ), the presets and the
// flags over them, --mask, --region, --diff, and the report of what differs where.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render/image.h"
#include "test_process.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;
using render::Image;
using test::CaseDir;
using test::Result;
using test::run_sluice;
using test::write_text;

// 100x50 images: a.png grey; b.png the same with a 4x2 block 5 levels brighter at
// (10, 20) (8 pixels, 0.16 %) and one pixel 100 levels darker at (70, 40).
constexpr int kW = 100, kH = 50;

Image grey() {
  Image img(kW, kH);
  std::fill(img.rgb.begin(), img.rgb.end(), std::uint8_t{128});
  return img;
}

void write_pair(const CaseDir& dir) {
  Image b = grey();
  for (int y = 20; y < 22; ++y)
    for (int x = 10; x < 14; ++x) b.at(x, y)[0] = 133;
  b.at(70, 40)[2] = 28;
  render::write_png((dir.work() / "a.png").string(), grey());
  render::write_png((dir.work() / "b.png").string(), b);
}

Result compare(const CaseDir& dir, std::vector<std::string> extra) {
  std::vector<std::string> args = {"compare", "a.png", "b.png"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_sluice(dir, args);
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "no '" << part << "' in:\n" << text;
}

TEST(CompareCli, SameImagesExit0) {
  CaseDir dir;
  write_pair(dir);
  const Result r = run_sluice(dir, {"compare", "a.png", "a.png", "--diff", "d.png"});
  EXPECT_EQ(r.status, 0) << r.err;
  expect_contains(r.out, "0 of 5000 pixels (0.0000%) differ by more than 0 levels; allowed 0.0000%: match");
  expect_contains(r.out, "differing pixels: none");
  EXPECT_FALSE(fs::exists(dir.work() / "d.png")) << "no diff image for equal images";
}

TEST(CompareCli, ReportsCountFractionLargestDifferenceAndBox) {
  CaseDir dir;
  write_pair(dir);
  const Result r = compare(dir, {"--diff", "d.png"});
  EXPECT_EQ(r.status, 1) << r.err;
  expect_contains(r.out,
                  "a.png vs b.png: 9 of 5000 pixels (0.1800%) differ by more than 0 levels; allowed 0.0000%: DIFFER");
  expect_contains(r.out, "largest difference: 100 levels at x = 70, y = 40");
  expect_contains(r.out, "differing pixels: bounding box x = 10, y = 20, w = 61, h = 21");
  expect_contains(r.out, "diff image: d.png");
  const Image d = render::read_png((dir.work() / "d.png").string());
  EXPECT_EQ(d.at(70, 40)[0], 255);          // differing: red
  EXPECT_EQ(d.at(0, 0)[0], d.at(0, 0)[2]);  // the same: grey
}

TEST(CompareCli, PresetsAndTheFlagsOverThem) {
  CaseDir dir;
  write_pair(dir);
  // strict (the default): any difference fails.
  EXPECT_EQ(compare(dir, {"--preset", "strict"}).status, 1);
  // tests: 8 levels, 0.5 %; only the dark pixel (0.02 %) is beyond 8 levels.
  Result r = compare(dir, {"--preset", "tests"});
  EXPECT_EQ(r.status, 0) << r.out;
  expect_contains(r.out, "1 of 5000 pixels (0.0200%) differ by more than 8 levels; allowed 0.5000%: match");
  // An explicit flag wins over the preset's value.
  EXPECT_EQ(compare(dir, {"--preset", "tests", "--max-fraction", "0"}).status, 1);
  r = compare(dir, {"--preset", "tests", "--tolerance", "4"});
  EXPECT_EQ(r.status, 0);
  expect_contains(r.out, "9 of 5000 pixels");
  EXPECT_EQ(compare(dir, {"--tolerance", "100"}).status, 0);
  EXPECT_EQ(compare(dir, {"--max-fraction", "0.002"}).status, 0);
  EXPECT_EQ(compare(dir, {"--max-fraction", "0.001"}).status, 1);
}

TEST(CompareCli, RegionsAreIgnored) {
  CaseDir dir;
  write_pair(dir);
  Result r = compare(dir, {"--region", "10,20,4,2", "--region", "70,40,1,1"});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  expect_contains(r.out, "0 of 4991 pixels");
  expect_contains(r.out, "ignored: 9 pixels");
  // Overlapping rectangles count each pixel once; the block alone leaves the dark pixel.
  r = compare(dir, {"--region", "0,0,50,50", "--region", "10,10,20,20"});
  EXPECT_EQ(r.status, 1);
  expect_contains(r.out, "1 of 2500 pixels");
  expect_contains(r.out, "bounding box x = 70, y = 40, w = 1, h = 1");
  // The whole image leaves nothing to compare: a usage error (IgnoringEveryPixelIsAUsageError).
  EXPECT_EQ(compare(dir, {"--region", "0,0,100,50"}).status, 2);
}

TEST(CompareCli, MaskIgnoresItsNonBlackPixels) {
  CaseDir dir;
  write_pair(dir);
  Image mask(kW, kH);      // black: compared
  mask.at(70, 40)[1] = 1;  // any non-black pixel is ignored, however dark
  for (int y = 20; y < 22; ++y)
    for (int x = 10; x < 14; ++x) mask.at(x, y)[0] = mask.at(x, y)[1] = mask.at(x, y)[2] = 255;
  render::write_png((dir.work() / "mask.png").string(), mask);
  Result r = compare(dir, {"--mask", "mask.png", "--diff", "d.png"});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  expect_contains(r.out, "0 of 4991 pixels");
  EXPECT_FALSE(fs::exists(dir.work() / "d.png"));
  // The block masked, the dark pixel left: the diff image shows the ignored pixels in
  // blue, the differing one in red.
  mask.at(70, 40)[1] = 0;
  render::write_png((dir.work() / "mask.png").string(), mask);
  r = compare(dir, {"--mask", "mask.png", "--region", "0,0,1,1", "--diff", "d.png"});
  EXPECT_EQ(r.status, 1);
  expect_contains(r.out, "ignored: 9 pixels");
  const Image d = render::read_png((dir.work() / "d.png").string());
  EXPECT_GT(d.at(10, 20)[2], d.at(10, 20)[0]);
  EXPECT_GT(d.at(0, 0)[2], d.at(0, 0)[0]);
  EXPECT_EQ(d.at(70, 40)[0], 255);
}

TEST(CompareCli, UsageErrorsExit2NamingTheFlagAndValue) {
  CaseDir dir;
  write_pair(dir);
  render::write_png((dir.work() / "small.png").string(), Image(10, 10));
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"--tolerance", "300"}, {"--tolerance"}},
      {{"--max-fraction", "2"}, {"--max-fraction", "<= 1", "'2'"}},
      {{"--preset", "loose"}, {"--preset", "loose", "strict,tests"}},
      {{"--region", "1,2,3"}, {"--region 1,2,3: expected x,y,w,h"}},
      {{"--region", "-1,0,3,3"}, {"--region -1,0,3,3: expected x,y,w,h", "x, y >= 0"}},
      {{"--region", "0,0,0,3"}, {"--region 0,0,0,3", "w, h >= 1"}},
      {{"--region", "90,0,20,10"},
       {"--region 90,0,20,10: the rectangle ends at x = 110", "outside the images (100x50)",
        "x + w <= 100 and y + h <= 50"}},
      {{"--mask", "small.png"}, {"--mask small.png: the mask is 10x10; it must have the images' size, 100x50"}},
      {{"--diff", "b.png"}, {"--diff b.png: it names the input image b.png"}},
      {{"--no-such-flag"}, {"--no-such-flag", "sluice compare --help"}},
  };
  for (const auto& [args, fragments] : cases) {
    SCOPED_TRACE(args.front() + (args.size() > 1 ? " " + args[1] : ""));
    const Result r = compare(dir, args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("sluice: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& f : fragments) expect_contains(r.err, f);
  }
  EXPECT_EQ(run_sluice(dir, {"compare", "a.png"}).status, 2) << "one image only";
}

// The diff image must not replace the mask either, however its path is spelled.
TEST(CompareCli, DiffMustNotNameTheMask) {
  CaseDir dir;
  write_pair(dir);
  Image mask(kW, kH);
  mask.at(70, 40)[0] = 255;
  render::write_png((dir.work() / "m.png").string(), mask);
  const std::string before = test::read_text(dir.work() / "m.png");
  for (const std::string diff : {"m.png", "./m.png"}) {
    SCOPED_TRACE(diff);
    const Result r = compare(dir, {"--mask", "m.png", "--diff", diff});
    EXPECT_EQ(r.status, 2) << r.err;
    expect_contains(r.err, "sluice: error: --diff " + diff + ": it names the mask m.png");
    EXPECT_EQ(test::read_text(dir.work() / "m.png"), before) << "the mask was overwritten";
  }
}

// Regions and a mask that leave nothing to compare would pass whatever the images hold.
TEST(CompareCli, IgnoringEveryPixelIsAUsageError) {
  CaseDir dir;
  write_pair(dir);
  Image white(kW, kH);
  std::fill(white.rgb.begin(), white.rgb.end(), std::uint8_t{255});
  render::write_png((dir.work() / "all.png").string(), white);
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--region", "0,0,100,50"}, "--region 0,0,100,50: they ignore all 100x50 pixels"},
      {{"--region", "0,0,100,25", "--region", "0,25,100,25"}, "--region 0,0,100,25 0,25,100,25: they ignore all"},
      {{"--mask", "all.png"}, "--mask all.png: they ignore all 100x50 pixels"},
      {{"--mask", "all.png", "--region", "0,0,1,1"}, "--mask and --region all.png 0,0,1,1: they ignore all"},
  };
  for (const auto& [args, fragment] : cases) {
    SCOPED_TRACE(fragment);
    const Result r = compare(dir, args);
    EXPECT_EQ(r.status, 2) << r.err;
    expect_contains(r.err, fragment);
    expect_contains(r.err, "which leaves nothing to compare");
    EXPECT_EQ(r.out.find("0 of 0 pixels"), std::string::npos) << r.out;
  }
}

TEST(CompareCli, UnreadableImagesExit3) {
  CaseDir dir;
  write_pair(dir);
  write_text(dir.work() / "text.png", "not a png");
  const std::string png = test::read_text(dir.work() / "b.png");
  write_text(dir.work() / "cut.png", png.substr(0, png.size() / 2));
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"compare", "missing.png", "a.png"},
           {"compare", "a.png", "text.png"},
           {"compare", "a.png", "cut.png"},
           {"compare", "a.png", "b.png", "--mask", "missing.png"},
       }) {
    SCOPED_TRACE(args[1] + " " + args[2]);
    const Result r = run_sluice(dir, args);
    EXPECT_EQ(r.status, 3) << r.err;
    expect_contains(r.err, "sluice: input image error: ");
  }
}

TEST(CompareCli, SizeMismatchExits4) {
  CaseDir dir;
  write_pair(dir);
  render::write_png((dir.work() / "wide.png").string(), Image(101, 50));
  const Result r = run_sluice(dir, {"compare", "a.png", "wide.png", "--preset", "tests"});
  EXPECT_EQ(r.status, 4) << r.err;
  expect_contains(r.out, "a.png is 100x50, wide.png is 101x50: sizes differ");
}

// The preset is the image tests' own rule: one constant for both (tests/test_render.cpp).
TEST(CompareCli, TestsPresetIsTheImageTestsRule) {
  EXPECT_EQ(render::kTestsRule.tolerance, 8);
  EXPECT_EQ(render::kTestsRule.max_fraction, 0.005);
  EXPECT_EQ(render::kStrictRule.tolerance, 0);
  EXPECT_EQ(render::kStrictRule.max_fraction, 0.0);
}

}  // namespace
}  // namespace sluice
