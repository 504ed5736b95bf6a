#pragma once
// RGB8 images in memory, PNG files (stb_image_write with libdeflate; stb_image to
// read) and the pixel comparison behind `sluice compare` and the image tests.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace sluice::render {

// A rendering, EGL or image file failure; the message names what failed.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An input image that cannot be opened or decoded (`sluice compare`'s own exit status:
// a missing golden image is not a missing GPU).
class ImageReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Rows top to bottom, 3 bytes per pixel, no padding.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, 0) {}
  std::uint8_t* at(int x, int y) { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
  const std::uint8_t* at(int x, int y) const { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
};

// PNG bytes of `img` (deflate level 1, "up" filter: fast and still compact).
std::vector<std::uint8_t> encode_png(const Image& img);
// Writes the PNG to `path` through `path.tmp` and a rename, so an existing file is
// complete; throws OutputError (io/atomic_file.h) naming the path and errno.
void write_png(const std::string& path, const Image& img);
// Reads a PNG (any channel count) as RGB; throws ImageReadError naming the file.
Image read_png(const std::string& path);

// When two images match: a pixel differs when its largest channel difference exceeds
// `tolerance` levels; the images match when at most `max_fraction` of the compared
// pixels differ.
struct CompareRule {
  int tolerance = 0;        // 0..255 levels
  double max_fraction = 0;  // 0..1
};
// `sluice compare --preset strict` (its default): every pixel equal.
inline constexpr CompareRule kStrictRule{0, 0.0};
// The image regression tests' rule and `sluice compare --preset tests`: Mesa's llvmpipe
// renders bit-identically, a GPU's EGL may differ by a few levels at disc edges.
inline constexpr CompareRule kTestsRule{8, 0.005};

struct CompareResult {
  bool same_size = false;
  long differing = 0;          // compared pixels whose largest channel difference exceeds the tolerance
  long total = 0;              // pixels compared (the image less the ignored ones)
  long ignored = 0;            // pixels left out by the mask
  int max_difference = 0;      // largest channel difference over the compared pixels
  int max_x = -1, max_y = -1;  // the first pixel (row order) with that difference; -1 when it is 0
  // Bounding box of the differing pixels, inclusive; -1 when none differs.
  int box_x0 = -1, box_y0 = -1, box_x1 = -1, box_y1 = -1;
  bool passed = false;
  double fraction() const { return total > 0 ? static_cast<double>(differing) / static_cast<double>(total) : 0.0; }
};

// One flag per pixel, row order: non-zero = left out of the comparison. Empty: none.
using PixelMask = std::vector<std::uint8_t>;

// A and B match when at most max_fraction of the compared pixels differ by more than
// `tolerance` levels in some channel (sizes must be equal).
CompareResult compare_images(const Image& a, const Image& b, int tolerance, double max_fraction,
                             const PixelMask& ignore = {});
// A faded grey copy of A with pixels differing by more than `tolerance` in red
// (brighter for larger differences) and ignored pixels in faded blue.
Image diff_image(const Image& a, const Image& b, int tolerance, const PixelMask& ignore = {});

}  // namespace sluice::render
