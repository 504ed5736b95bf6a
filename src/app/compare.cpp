// `sluice compare A.png B.png`: pixel comparison of two images for image regression in CI,
// with presets, ignored regions and a report of where the images differ.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "render/image.h"
#include "view/scene_view.h"

namespace sluice::app {

namespace fs = std::filesystem;
using render::CompareResult;
using render::CompareRule;
using render::Image;
using render::PixelMask;
using view::FlagError;

namespace {

struct Rect {
  long x = 0, y = 0, w = 0, h = 0;
};

const char* const kRegionAllowed =
    "expected x,y,w,h: whole numbers with x, y >= 0 and w, h >= 1 (pixels, from the top left)";

// "x,y,w,h"; throws FlagError. Checked against the images' size once they are read.
Rect parse_region(const std::string& text) {
  long v[4];
  const char* p = text.c_str();
  for (int k = 0; k < 4; ++k) {
    char* end = nullptr;
    errno = 0;
    v[k] = std::strtol(p, &end, 10);
    const bool digit = *p >= '0' && *p <= '9';  // no sign, no space
    if (!digit || end == p || errno != 0 || *end != (k < 3 ? ',' : '\0'))
      throw FlagError("--region", text, kRegionAllowed);
    p = end + 1;
  }
  if (v[2] < 1 || v[3] < 1) throw FlagError("--region", text, kRegionAllowed);
  return {v[0], v[1], v[2], v[3]};
}

void check_inside(const Rect& r, const std::string& text, const Image& img) {
  if (r.x + r.w <= img.width && r.y + r.h <= img.height) return;
  throw FlagError("--region", text,
                  "the rectangle ends at x = " + std::to_string(r.x + r.w) + ", y = " + std::to_string(r.y + r.h) +
                      ", outside the images (" + std::to_string(img.width) + "x" + std::to_string(img.height) +
                      "); allowed: x + w <= " + std::to_string(img.width) +
                      " and y + h <= " + std::to_string(img.height));
}

// The pixels left out: the mask's non-black pixels and every --region rectangle.
PixelMask ignored_pixels(const CompareOptions& o, const std::vector<Rect>& regions, const Image& img) {
  if (o.mask.empty() && regions.empty()) return {};
  PixelMask ignore(static_cast<size_t>(img.width) * img.height, 0);
  if (!o.mask.empty()) {
    const Image m = render::read_png(o.mask);
    if (m.width != img.width || m.height != img.height)
      throw FlagError("--mask", o.mask,
                      "the mask is " + std::to_string(m.width) + "x" + std::to_string(m.height) +
                          "; it must have the images' size, " + std::to_string(img.width) + "x" +
                          std::to_string(img.height));
    for (size_t i = 0; i < ignore.size(); ++i) ignore[i] = (m.rgb[3 * i] | m.rgb[3 * i + 1] | m.rgb[3 * i + 2]) != 0;
  }
  for (size_t k = 0; k < regions.size(); ++k) {
    check_inside(regions[k], o.regions[k], img);
    for (long y = regions[k].y; y < regions[k].y + regions[k].h; ++y)
      for (long x = regions[k].x; x < regions[k].x + regions[k].w; ++x)
        ignore[static_cast<size_t>(y) * img.width + x] = 1;
  }
  return ignore;
}

// The preset's rule with --tolerance and --max-fraction over it.
CompareRule rule_of(const CompareOptions& o) {
  CompareRule r = o.preset == "tests" ? render::kTestsRule : render::kStrictRule;
  if (o.tolerance >= 0) r.tolerance = o.tolerance;
  if (o.max_fraction >= 0) r.max_fraction = o.max_fraction;
  return r;
}

// The diff image must not replace an input (compare --diff A.png A.png B.png), the mask
// included, nor be a folder. equivalent() sees through links and other spellings of a path.
void check_diff_path(const CompareOptions& o) {
  if (o.diff.empty()) return;
  std::error_code ec;
  const std::pair<const std::string*, const char*> inputs[] = {
      {&o.a, "input image "}, {&o.b, "input image "}, {&o.mask, "mask "}};
  for (const auto& [in, what] : inputs)
    if (!in->empty() && fs::equivalent(o.diff, *in, ec))
      throw FlagError("--diff", o.diff,
                      "it names the " + std::string(what) + *in + "; choose another path for the diff image");
  if (fs::is_directory(o.diff, ec))
    throw FlagError("--diff", o.diff, "is a directory; --diff takes the PNG file to write");
}

void print_report(const CompareOptions& o, const CompareRule& rule, const CompareResult& r) {
  std::printf("%s vs %s: %ld of %ld pixels (%.4f%%) differ by more than %d levels; allowed %.4f%%: %s\n", o.a.c_str(),
              o.b.c_str(), r.differing, r.total, 100.0 * r.fraction(), rule.tolerance, 100.0 * rule.max_fraction,
              r.passed ? "match" : "DIFFER");
  if (r.max_difference > 0)
    std::printf("largest difference: %d levels at x = %d, y = %d\n", r.max_difference, r.max_x, r.max_y);
  else
    std::printf("largest difference: 0 levels\n");
  if (r.differing > 0)
    std::printf("differing pixels: bounding box x = %d, y = %d, w = %d, h = %d\n", r.box_x0, r.box_y0,
                r.box_x1 - r.box_x0 + 1, r.box_y1 - r.box_y0 + 1);
  else
    std::printf("differing pixels: none\n");
  if (r.ignored > 0) std::printf("ignored: %ld pixels (--mask, --region)\n", r.ignored);
}

}  // namespace

int run_compare(const CompareOptions& o) {
  std::vector<Rect> regions;
  for (const std::string& text : o.regions) regions.push_back(parse_region(text));
  check_diff_path(o);
  const CompareRule rule = rule_of(o);
  const Image a = render::read_png(o.a), b = render::read_png(o.b);
  if (a.width != b.width || a.height != b.height) {
    std::printf("%s is %dx%d, %s is %dx%d: sizes differ\n", o.a.c_str(), a.width, a.height, o.b.c_str(), b.width,
                b.height);
    return kCompareSize;
  }
  const PixelMask ignore = ignored_pixels(o, regions, a);
  // Nothing left to compare would pass ("0 of 0 pixels") whatever the images hold.
  if (!ignore.empty() && std::find(ignore.begin(), ignore.end(), 0) == ignore.end()) {
    const std::string flags = o.mask.empty() ? "--region" : o.regions.empty() ? "--mask" : "--mask and --region";
    std::string value = o.mask;
    for (const std::string& r : o.regions) value += (value.empty() ? "" : " ") + r;
    throw FlagError(flags, value,
                    "they ignore all " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                        " pixels of the images, which leaves nothing to compare; ignore less");
  }
  const CompareResult r = render::compare_images(a, b, rule.tolerance, rule.max_fraction, ignore);
  print_report(o, rule, r);
  if (!o.diff.empty() && r.differing > 0) {
    render::write_png(o.diff, render::diff_image(a, b, rule.tolerance, ignore));
    std::printf("diff image: %s\n", o.diff.c_str());
  }
  return r.passed ? kCompareSame : kCompareDifferent;
}

}  // namespace sluice::app
