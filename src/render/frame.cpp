#include "render/frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "render/font.h"

namespace sluice::render {

namespace {

constexpr Rgb kBackground{255, 255, 255};
constexpr Rgb kWall{150, 150, 150};        // boundaries at rest: neutral grey
constexpr Rgb kMovingWall{84, 100, 124};   // moving boundaries: darker slate
constexpr Rgb kInk{25, 25, 25};
constexpr Rgb kPanel{245, 245, 245};
constexpr int kTickCount = 5;
constexpr int kLabelChars = 7;
constexpr double kMargin = 0.04;  // share of the image left free around the scene

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int colorbar_strip_width(const FrameSettings& s, int scale) {
  if (!s.colorbar) return 0;
  const int labels = std::max(text_width(std::string(kLabelChars, '0'), scale) + 10 * scale,
                              text_width(s.field_label, scale) - 6 * scale);
  return 6 * scale + 6 * scale + labels + 6 * scale;  // pad, bar, ticks + labels, pad
}

int overlay_height(int scale) { return (kGlyphHeight + 6) * scale; }

}  // namespace

std::string tick_label(double v) {
  char buf[32];
  if (v == 0) return "0";
  const double a = std::fabs(v);
  if (a >= 1e-2 && a < 1e4)
    std::snprintf(buf, sizeof buf, "%.4g", v);
  else
    std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

FrameLayout fit_layout(const FrameSettings& s) {
  FrameLayout L;
  L.scale = std::max(1, s.height / 240);
  const int strip = colorbar_strip_width(s, L.scale);
  const int top = s.overlay ? overlay_height(L.scale) : 0;  // the overlay line never covers the scene
  const double avail_w = std::max(1, s.width - strip), avail_h = std::max(1, s.height - top);
  const double sw = std::max(1e-9, s.bounds_max[0] - s.bounds_min[0]);
  const double sh = std::max(1e-9, s.bounds_max[1] - s.bounds_min[1]);
  const double margin = s.fit_margin ? kMargin * std::min(avail_w, avail_h) : 0.0;
  L.pixels_per_metre = std::max(1e-9, std::min((avail_w - 2 * margin) / sw, (avail_h - 2 * margin) / sh));
  const double cx = 0.5 * (s.bounds_min[0] + s.bounds_max[0]), cy = 0.5 * (s.bounds_min[1] + s.bounds_max[1]);
  L.view.x0 = cx - 0.5 * avail_w / L.pixels_per_metre;
  L.view.x1 = L.view.x0 + s.width / L.pixels_per_metre;
  L.view.y1 = cy + (0.5 * avail_h + top) / L.pixels_per_metre;
  L.view.y0 = L.view.y1 - s.height / L.pixels_per_metre;
  if (s.colorbar) {
    L.bar_w = 6 * L.scale;
    L.bar_h = s.height * 3 / 5;
    L.bar_x = s.width - strip + 6 * L.scale;
    L.bar_y = (s.height - L.bar_h) / 2;
  }
  return L;
}

FrameRenderer::FrameRenderer(const FrameSettings& s)
    : s_(s), layout_(fit_layout(s)), cmap_(s.colormap), gl_(s.width, s.height, s.msaa, s.egl) {}

void draw_colorbar_bar(Image& img, int x, int y, int w, int h, int s, const Colormap& cmap, double lo, double hi) {
  // The bar, top = hi.
  for (int j = 0; j < h; ++j) fill_rect(img, x, y + j, w, 1, cmap.at(1.0 - (j + 0.5) / h));
  // Frame around it and ticks with labels.
  fill_rect(img, x - 1, y - 1, w + 2, 1, kInk);
  fill_rect(img, x - 1, y + h, w + 2, 1, kInk);
  fill_rect(img, x - 1, y - 1, 1, h + 2, kInk);
  fill_rect(img, x + w, y - 1, 1, h + 2, kInk);
  for (int k = 0; k < kTickCount; ++k) {
    const double f = static_cast<double>(k) / (kTickCount - 1);
    const int ty = y + h - static_cast<int>(std::lround(f * (h - 1))) - 1;
    fill_rect(img, x + w, ty, 2 * s, std::max(1, s / 2), kInk);
    draw_text(img, x + w + 4 * s, ty - kGlyphHeight * s / 2, tick_label(lo + f * (hi - lo)), s, kInk);
  }
}

namespace {

void draw_colorbar(Image& img, const FrameLayout& L, const Colormap& cmap, double lo, double hi,
                   const std::string& title) {
  const int s = L.scale;
  // The strip is the colorbar's own: particles outside the view window may reach it.
  fill_rect(img, L.bar_x - 6 * s, 0, img.width - (L.bar_x - 6 * s), img.height, kBackground);
  draw_colorbar_bar(img, L.bar_x, L.bar_y, L.bar_w, L.bar_h, s, cmap, lo, hi);
  const int tw = text_width(title, s);
  const int tx = std::min(L.bar_x, img.width - tw - 2 * s);
  draw_text(img, tx, L.bar_y - (kGlyphHeight + 5) * s, title, s, kInk);
}

void draw_overlay(Image& img, const FrameLayout& L, const std::string& text) {
  const int s = L.scale;
  fill_rect(img, 0, 0, img.width, overlay_height(s), kBackground);  // the line's own band, as the colorbar's strip
  fill_rect(img, 0, 0, text_width(text, s) + 8 * s, overlay_height(s), kPanel);
  draw_text(img, 4 * s, 3 * s, text, s, kInk);
}

}  // namespace

void FrameRenderer::render(const FrameData& d, Image& out) {
  auto t0 = std::chrono::steady_clock::now();
  const size_t nb = d.boundary_xy.size() / 2;
  boundary_rgb_.resize(nb);
  for (size_t i = 0; i < nb; ++i)
    boundary_rgb_[i] = (i < d.boundary_moving.size() && d.boundary_moving[i]) ? kMovingWall : kWall;
  cmap_.map(d.fluid_value, d.lo, d.hi, fluid_rgb_);
  gl_.clear(kBackground);
  gl_.draw_discs(layout_.view, d.diameter, d.boundary_xy, boundary_rgb_);
  gl_.draw_discs(layout_.view, d.diameter, d.fluid_xy, fluid_rgb_);
  gl_.finish();
  timings_.draw = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  gl_.read(out);
  timings_.read = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  if (s_.colorbar) draw_colorbar(out, layout_, cmap_, d.lo, d.hi, s_.field_label);
  if (s_.overlay && !d.overlay.empty()) draw_overlay(out, layout_, d.overlay);
  timings_.annotate = ms_since(t0);
}

}  // namespace sluice::render
