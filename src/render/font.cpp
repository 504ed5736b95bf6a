#include "render/font.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

// The font file itself, assembled into the program (SLUICE_FONT_PATH comes from CMake).
asm(".section .rodata\n"
    ".balign 16\n"
    "sluice_font_begin:\n"
    ".incbin \"" SLUICE_FONT_PATH
    "\"\n"
    "sluice_font_end:\n"
    ".byte 0\n"
    ".previous\n");
extern "C" const unsigned char sluice_font_begin[], sluice_font_end[];

namespace sluice::render {

namespace {

struct Font {
  stbtt_fontinfo info{};
  int ascent = 0, descent = 0;  // font units
  Font() {
    stbtt_InitFont(&info, sluice_font_begin, stbtt_GetFontOffsetForIndex(sluice_font_begin, 0));
    int gap = 0;
    stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
  }
  float scale(int px) const { return stbtt_ScaleForPixelHeight(&info, static_cast<float>(px)); }
};

const Font& font() {
  static const Font f;  // read-only after construction: safe from any thread
  return f;
}

// The next code point of UTF-8 `s` at `i` (advanced); U+FFFD for a malformed sequence.
int next_codepoint(std::string_view s, size_t& i) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned c = b(i++);
  if (c < 0x80) return static_cast<int>(c);
  const int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : -1;
  if (extra < 0 || i + extra > s.size()) return 0xFFFD;
  int cp = static_cast<int>(c & (0x3F >> extra));
  for (int k = 0; k < extra; ++k) {
    if ((b(i) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (b(i++) & 0x3F);
  }
  return cp;
}

std::vector<int> glyphs_of(std::string_view text) {
  std::vector<int> g;
  for (size_t i = 0; i < text.size();) g.push_back(stbtt_FindGlyphIndex(&font().info, next_codepoint(text, i)));
  return g;
}

// Pen positions (in pixels, fractional) of each glyph and the end of the line.
std::vector<float> pen_positions(const std::vector<int>& g, float scale) {
  std::vector<float> pen(g.size() + 1, 0.0f);
  for (size_t k = 0; k < g.size(); ++k) {
    int advance = 0, lsb = 0;
    stbtt_GetGlyphHMetrics(&font().info, g[k], &advance, &lsb);
    int kern = k + 1 < g.size() ? stbtt_GetGlyphKernAdvance(&font().info, g[k], g[k + 1]) : 0;
    pen[k + 1] = pen[k] + scale * static_cast<float>(advance + kern);
  }
  return pen;
}

std::uint8_t blend(std::uint8_t under, std::uint8_t ink, int alpha) {
  return static_cast<std::uint8_t>((under * (255 - alpha) + ink * alpha + 127) / 255);
}

}  // namespace

int text_ascent(int px) { return static_cast<int>(std::ceil(font().scale(px) * static_cast<float>(font().ascent))); }

int line_height(int px) {
  return static_cast<int>(std::ceil(font().scale(px) * static_cast<float>(font().ascent - font().descent)));
}

int text_width(std::string_view text, int px) {
  const std::vector<int> g = glyphs_of(text);
  return static_cast<int>(std::ceil(pen_positions(g, font().scale(px)).back()));
}

int fit_text_size(std::string_view text, int px, int width, int min_px) {
  while (px > min_px && text_width(text, px) > width) --px;
  return px;
}

void fill_rect(Image& img, int x, int y, int w, int h, Rgb color) {
  const int x0 = std::max(0, x), y0 = std::max(0, y);
  const int x1 = std::min(img.width, x + w), y1 = std::min(img.height, y + h);
  for (int j = y0; j < y1; ++j)
    for (int i = x0; i < x1; ++i) {
      std::uint8_t* p = img.at(i, j);
      p[0] = color.r;
      p[1] = color.g;
      p[2] = color.b;
    }
}

void draw_text(Image& img, int x, int y, std::string_view text, int px, Rgb color) {
  const float scale = font().scale(px);
  const std::vector<int> g = glyphs_of(text);
  const std::vector<float> pen = pen_positions(g, scale);
  const int baseline = y + text_ascent(px);
  std::vector<unsigned char> coverage;
  for (size_t k = 0; k < g.size(); ++k) {
    // Whole pixels for the glyph's origin, the fraction as stb's sub-pixel shift: glyph
    // spacing stays even at small sizes.
    const float fx = std::floor(pen[k]), shift = pen[k] - fx;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    stbtt_GetGlyphBitmapBoxSubpixel(&font().info, g[k], scale, scale, shift, 0.0f, &x0, &y0, &x1, &y1);
    const int w = x1 - x0, h = y1 - y0;
    if (w <= 0 || h <= 0) continue;
    coverage.assign(static_cast<size_t>(w) * h, 0);
    stbtt_MakeGlyphBitmapSubpixel(&font().info, coverage.data(), w, h, w, scale, scale, shift, 0.0f, g[k]);
    const int ox = x + static_cast<int>(fx) + x0, oy = baseline + y0;
    for (int j = 0; j < h; ++j) {
      if (oy + j < 0 || oy + j >= img.height) continue;
      for (int i = 0; i < w; ++i) {
        const int a = coverage[static_cast<size_t>(j) * w + i];
        if (a == 0 || ox + i < 0 || ox + i >= img.width) continue;
        std::uint8_t* p = img.at(ox + i, oy + j);
        p[0] = blend(p[0], color.r, a);
        p[1] = blend(p[1], color.g, a);
        p[2] = blend(p[2], color.b, a);
      }
    }
  }
}

}  // namespace sluice::render
