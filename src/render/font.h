#pragma once
// Text drawn into RGB images on the CPU (after read-back) with stb_truetype from the
// TrueType font chosen at build time (CMake's SLUICE_FONT, DejaVu Sans from
// fonts-dejavu-core by default) and embedded in the program, so images never depend on
// the fonts of the machine that runs it. Text is UTF-8; characters the font lacks draw
// as its missing-glyph box. Sizes are pixel heights (ascent to descent).
#include <string_view>

#include "render/colormap.h"
#include "render/image.h"

namespace sluice::render {

// Width in pixels of `text` at pixel height `px` (the advance, rounded up).
int text_width(std::string_view text, int px);
// Ink rows of a line at `px`: the baseline sits ascent(px) below the line's top.
int text_ascent(int px);
int line_height(int px);  // ascent + descent, rounded up
// Draws `text` with the top of its line at y and its pen starting at x; anti-aliased
// over what is there; clipped to the image.
void draw_text(Image& img, int x, int y, std::string_view text, int px, Rgb color);
// The largest pixel height <= px at which `text` fits `width` (at least `min_px`).
int fit_text_size(std::string_view text, int px, int width, int min_px = 6);
// Fills a rectangle, clipped to the image.
void fill_rect(Image& img, int x, int y, int w, int h, Rgb color);

}  // namespace sluice::render
