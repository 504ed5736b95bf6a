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

struct CompareResult {
  bool same_size = false;
  long differing = 0;      // pixels whose largest channel difference exceeds the tolerance
  long total = 0;
  int max_difference = 0;  // largest channel difference over the image
  bool passed = false;
};

// A and B match when at most max_fraction of the pixels differ by more than
// `tolerance` levels in some channel (sizes must be equal).
CompareResult compare_images(const Image& a, const Image& b, int tolerance, double max_fraction);
// A faded grey copy of A with pixels differing by more than `tolerance` in red
// (brighter for larger differences).
Image diff_image(const Image& a, const Image& b, int tolerance);

}  // namespace sluice::render
