#include "render/frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "render/font.h"

namespace sluice::render {

namespace {

constexpr Rgb kWall{150, 150, 150};  // boundary samples without a colour of their own
constexpr Rgb kInk{25, 25, 25};
constexpr Rgb kPanel{245, 245, 245};
constexpr double kMargin = 0.04;  // share of the image left free around the scene
constexpr int kTickTarget = 5;
// Tick labels are at most this wide (tick_label keeps 4 significant digits or uses an
// exponent): the strip reserves it whatever the range, so fields line up.
constexpr const char* kWidestTick = "-0.0025";

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Labels grow with the image: 20 px at 720 rows, 10 px (the least that reads) at 360 and below.
int frame_text_px(int height) { return std::max(10, static_cast<int>(std::lround(height / 36.0))); }

// Top of a label whose digits are centred on row `y`.
int centred_top(int y, int px) { return y - text_ascent(px) + (px * 63 / 100) / 2; }

}  // namespace

double nice_step(double lo, double hi, int target) {
  const double range = hi - lo;
  if (!(range > 0) || !std::isfinite(range)) return 1;
  const double raw = range / std::max(1, target - 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(hi - lo)) return ticks;  // no range to divide
  const double step = nice_step(lo, hi, target);
  // Integer multiples of the step (k * step, never accumulated sums: 0.1 + 0.2 != 0.3).
  const double eps = 1e-9 * step;
  for (long k = static_cast<long>(std::ceil((lo - eps) / step)); static_cast<double>(k) * step <= hi + eps; ++k)
    ticks.push_back(k == 0 ? 0.0 : static_cast<double>(k) * step);
  return ticks;
}

std::string tick_label(double v, double step) {
  char buf[32];
  if (v == 0) return "0";
  const double a = std::max(std::fabs(v), step);
  if (a >= 1e-3 && a < 1e5) {
    const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 4);
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  } else {
    std::snprintf(buf, sizeof buf, "%.1e", v);
  }
  return buf;
}

int colorbar_label_width(int px) { return px / 3 + px / 4 + text_width(kWidestTick, px); }

int colorbar_width(int px, int bar_w) {
  return std::max(bar_w + colorbar_label_width(px), text_width("density error [%]", px));
}

FrameLayout fit_layout(const FrameSettings& s) {
  FrameLayout L;
  L.text_px = frame_text_px(s.height);
  L.pad = std::max(2, L.text_px / 3);
  const int rows = (s.overlay ? 1 : 0) + (s.title.empty() ? 0 : 1);
  L.band_h = rows ? rows * (line_height(L.text_px) + L.pad) + L.pad : 0;
  if (s.colorbar) {
    L.bar_w = std::max(6, L.text_px * 3 / 4);
    // gap to the scene, bar, ticks and labels, right pad; the field's name above the bar
    // is sized to this width rather than the width to the name.
    L.strip_w = 2 * L.pad + colorbar_width(L.text_px, L.bar_w) + L.pad;
  }
  const double avail_w = std::max(1, s.width - L.strip_w), avail_h = std::max(1, s.height - L.band_h);
  const double sw = std::max(1e-9, s.bounds_max[0] - s.bounds_min[0]);
  const double sh = std::max(1e-9, s.bounds_max[1] - s.bounds_min[1]);
  const double margin = s.fit_margin ? kMargin * std::min(avail_w, avail_h) : 0.0;
  L.pixels_per_metre = std::max(1e-9, std::min((avail_w - 2 * margin) / sw, (avail_h - 2 * margin) / sh));
  // The scene and the colorbar strip as one group, centred: the bar sits beside the
  // scene, whatever is left over goes to both sides.
  const double scene_w = sw * L.pixels_per_metre, scene_h = sh * L.pixels_per_metre;
  const double left = 0.5 * (s.width - (scene_w + 2 * margin + L.strip_w)) + margin;
  const double top = L.band_h + 0.5 * (avail_h - scene_h);
  L.view.x0 = s.bounds_min[0] - left / L.pixels_per_metre;
  L.view.x1 = L.view.x0 + s.width / L.pixels_per_metre;
  L.view.y1 = s.bounds_max[1] + top / L.pixels_per_metre;
  L.view.y0 = L.view.y1 - s.height / L.pixels_per_metre;
  L.scene_x0 = static_cast<int>(std::lround(left));
  L.scene_x1 = static_cast<int>(std::lround(left + scene_w));
  L.scene_y0 = static_cast<int>(std::lround(top));
  L.scene_y1 = static_cast<int>(std::lround(top + scene_h));
  if (s.colorbar) {
    L.strip_x = std::min(s.width - L.strip_w, static_cast<int>(std::lround(left + scene_w + margin)));
    L.bar_x = L.strip_x + 2 * L.pad;
    L.bar_h = static_cast<int>(avail_h * 3 / 5);
    L.bar_y = L.band_h + (static_cast<int>(avail_h) - L.bar_h) / 2;
  }
  return L;
}

FrameRenderer::FrameRenderer(const FrameSettings& s)
    : s_(s), layout_(fit_layout(s)), cmap_(s.colormap), gl_(s.width, s.height, s.msaa, s.egl) {}

Rgb ink_on(Rgb bg) {
  const int luma = (299 * bg.r + 587 * bg.g + 114 * bg.b) / 1000;  // Rec. 601 weights
  return luma >= 128 ? kInk : Rgb{235, 235, 235};
}

void draw_colorbar_bar(Image& img, int x, int y, int w, int h, int px, const Colormap& cmap, double lo, double hi,
                       Rgb ink) {
  // The bar, top = hi.
  for (int j = 0; j < h; ++j) fill_rect(img, x, y + j, w, 1, cmap.at(1.0 - (j + 0.5) / h));
  // Frame around it and ticks with labels.
  fill_rect(img, x - 1, y - 1, w + 2, 1, ink);
  fill_rect(img, x - 1, y + h, w + 2, 1, ink);
  fill_rect(img, x - 1, y - 1, 1, h + 2, ink);
  fill_rect(img, x + w, y - 1, 1, h + 2, ink);
  const double step = nice_step(lo, hi, kTickTarget);
  for (double v : nice_ticks(lo, hi, kTickTarget)) {
    const double f = (v - lo) / (hi - lo);
    const int ty = y + h - static_cast<int>(std::lround(f * (h - 1))) - 1;
    fill_rect(img, x + w, ty, px / 3, std::max(1, px / 10), ink);
    draw_text(img, x + w + px / 3 + px / 4, centred_top(ty, px), tick_label(v, step), px, ink);
  }
}

namespace {

void draw_colorbar(Image& img, const FrameLayout& L, const Colormap& cmap, double lo, double hi,
                   const std::string& title, Rgb background) {
  // The strip is the colorbar's own: particles outside the view window may reach it.
  fill_rect(img, L.strip_x, L.band_h, img.width - L.strip_x, img.height - L.band_h, background);
  const Rgb ink = ink_on(background);
  draw_colorbar_bar(img, L.bar_x, L.bar_y, L.bar_w, L.bar_h, L.text_px, cmap, lo, hi, ink);
  // The field's name above the bar, smaller when it would leave the strip.
  const int room = img.width - L.bar_x - L.pad;
  const int px = fit_text_size(title, L.text_px, room);
  // Half a line clear of the top tick's label, which is centred on the bar's top.
  draw_text(img, L.bar_x, L.bar_y - line_height(L.text_px) - L.text_px / 2, title, px, ink);
}

// The top band: title row, then overlay row. Its size is fixed by fit_layout.
void draw_band(Image& img, const FrameLayout& L, const std::string& title, const std::string& overlay) {
  fill_rect(img, 0, 0, img.width, L.band_h, kPanel);
  fill_rect(img, 0, L.band_h - 1, img.width, 1, {225, 225, 225});
  int y = L.pad;
  const int room = img.width - 2 * L.pad;
  if (!title.empty()) {
    draw_text(img, L.pad, y, title, fit_text_size(title, L.text_px, room), kInk);
    y += line_height(L.text_px) + L.pad;
  }
  if (!overlay.empty()) draw_text(img, L.pad, y, overlay, fit_text_size(overlay, L.text_px, room), kInk);
}

}  // namespace

void FrameRenderer::render(const FrameData& d, Image& out) {
  auto t0 = std::chrono::steady_clock::now();
  const size_t nb = d.boundary_xy.size() / 2;
  boundary_rgb_.resize(nb);
  for (size_t i = 0; i < nb; ++i) boundary_rgb_[i] = i < d.boundary_rgb.size() ? d.boundary_rgb[i] : kWall;
  cmap_.map(d.fluid_value, d.lo, d.hi, fluid_rgb_);
  gl_.clear(s_.background);
  const double diameter = d.diameter * s_.particle_scale;
  gl_.draw_discs(layout_.view, diameter, d.boundary_xy, boundary_rgb_);
  gl_.draw_discs(layout_.view, diameter, d.fluid_xy, fluid_rgb_);
  gl_.finish();
  timings_.draw = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  gl_.read(out);
  timings_.read = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  if (s_.colorbar) draw_colorbar(out, layout_, cmap_, d.lo, d.hi, s_.field_label, s_.background);
  if (layout_.band_h > 0) draw_band(out, layout_, s_.title, s_.overlay ? d.overlay : std::string());
  timings_.annotate = ms_since(t0);
}

}  // namespace sluice::render
