#pragma once
// A small 5x7 bitmap font drawn into RGB images on the CPU (after read-back), for
// the colorbar labels and the overlay line. Lower-case letters draw as upper case;
// characters without a glyph draw as a box.
#include <string_view>

#include "render/colormap.h"
#include "render/image.h"

namespace sluice::render {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

// Width in pixels of `text` at integer `scale` (each font pixel is scale x scale).
int text_width(std::string_view text, int scale);
// Draws `text` with its top-left corner at (x, y); clipped to the image.
void draw_text(Image& img, int x, int y, std::string_view text, int scale, Rgb color);
// Fills a rectangle, clipped to the image.
void fill_rect(Image& img, int x, int y, int w, int h, Rgb color);

}  // namespace sluice::render
