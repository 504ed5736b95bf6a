// PNG encoding through stb_image_write with libdeflate as its zlib compressor: stb's own
// deflate is several times slower on a 1080p frame than libdeflate at level 1 with the
// "up" filter (docs/performance.md, the frame-time table).
#include "render/image.h"

#include "io/atomic_file.h"

#include <libdeflate.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace {

// stb calls this for the IDAT stream; the buffer must come from malloc (stb frees it).
unsigned char* deflate_for_stb(unsigned char* data, int data_len, int* out_len, int /*quality*/) {
  libdeflate_compressor* c = libdeflate_alloc_compressor(1);
  if (!c) return nullptr;
  const size_t bound = libdeflate_zlib_compress_bound(c, static_cast<size_t>(data_len));
  auto* out = static_cast<unsigned char*>(std::malloc(bound));
  size_t n = out ? libdeflate_zlib_compress(c, data, static_cast<size_t>(data_len), out, bound) : 0;
  libdeflate_free_compressor(c);
  if (n == 0) {
    std::free(out);
    return nullptr;
  }
  *out_len = static_cast<int>(n);
  return out;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS deflate_for_stb
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>

namespace sluice::render {

std::vector<std::uint8_t> encode_png(const Image& img) {
  stbi_write_force_png_filter = 2;  // "up": cheap and good on flat-coloured renders
  int len = 0;
  unsigned char* png = stbi_write_png_to_mem(img.rgb.data(), img.width * 3, img.width, img.height, 3, &len);
  if (!png) throw RenderError("PNG encoding failed (out of memory?)");
  std::vector<std::uint8_t> out(png, png + len);
  STBIW_FREE(png);
  return out;
}

void write_png(const std::string& path, const Image& img) {
  const std::vector<std::uint8_t> png = encode_png(img);
  write_bytes_atomic(path, png.data(), png.size());
}

Image read_png(const std::string& path) {
  // stb says only "can't fopen": the errno says why (missing, a folder, no permission).
  errno = 0;
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw ImageReadError(path + ": cannot open PNG: " + std::strerror(errno));
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load_from_file(f, &w, &h, &channels, 3);
  std::fclose(f);
  if (!data) throw ImageReadError(path + ": cannot read PNG: " + stbi_failure_reason());
  Image img(w, h);
  std::copy(data, data + img.rgb.size(), img.rgb.begin());
  stbi_image_free(data);
  return img;
}

namespace {
int pixel_difference(const Image& a, const Image& b, size_t i) {
  int d = 0;
  for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.rgb[i * 3 + c]) - int(b.rgb[i * 3 + c])));
  return d;
}
}  // namespace

CompareResult compare_images(const Image& a, const Image& b, int tolerance, double max_fraction,
                             const PixelMask& ignore) {
  CompareResult r;
  r.same_size = a.width == b.width && a.height == b.height;
  if (!r.same_size) return r;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const size_t i = static_cast<size_t>(y) * a.width + x;
      if (!ignore.empty() && ignore[i]) {
        ++r.ignored;
        continue;
      }
      ++r.total;
      const int d = pixel_difference(a, b, i);
      if (d > r.max_difference) {
        r.max_difference = d;
        r.max_x = x;
        r.max_y = y;
      }
      if (d <= tolerance) continue;
      ++r.differing;
      if (r.box_x0 < 0) {
        r.box_x0 = r.box_x1 = x;
        r.box_y0 = r.box_y1 = y;
      }
      r.box_x0 = std::min(r.box_x0, x);
      r.box_x1 = std::max(r.box_x1, x);
      r.box_y1 = y;  // rows come in order
    }
  r.passed = static_cast<double>(r.differing) <= max_fraction * static_cast<double>(r.total);
  return r;
}

Image diff_image(const Image& a, const Image& b, int tolerance, const PixelMask& ignore) {
  Image out(a.width, a.height);
  const bool same = a.width == b.width && a.height == b.height;
  for (size_t i = 0; i < static_cast<size_t>(a.width) * a.height; ++i) {
    const std::uint8_t* p = &a.rgb[i * 3];
    const int grey = 192 + (p[0] + p[1] + p[2]) / 12;  // faded context: 192..255
    const int d = same ? pixel_difference(a, b, i) : 255;
    std::uint8_t* q = &out.rgb[i * 3];
    if (!ignore.empty() && ignore[i]) {
      q[0] = q[1] = static_cast<std::uint8_t>(grey - 40);
      q[2] = static_cast<std::uint8_t>(grey);
    } else if (d > tolerance) {
      q[0] = 255;
      q[1] = q[2] = static_cast<std::uint8_t>(std::max(0, 160 - d * 2));
    } else {
      q[0] = q[1] = q[2] = static_cast<std::uint8_t>(grey);
    }
  }
  return out;
}

}  // namespace sluice::render
