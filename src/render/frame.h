#pragma once
// One frame of a particle scene: the view fitted to the scene's bounds, fluid discs
// coloured by a field through a colormap, boundary discs in grey, a colorbar with
// labelled ticks and an optional overlay line. Solver-agnostic: it takes arrays.
#include <cstdint>
#include <span>
#include <string>

#include "render/colormap.h"
#include "render/gl_renderer.h"

namespace sluice::render {

struct FrameSettings {
  int width = 1280, height = 720;
  int msaa = 0;                    // 0 or 4
  EglPlatform egl = EglPlatform::automatic;
  ColormapName colormap = ColormapName::spectrum;
  std::string field_label = "CFL";  // title above the colorbar
  bool colorbar = true;
  bool overlay = true;
  // The world box to show, centred with the aspect ratio kept; with fit_margin a margin
  // of a few percent of the image surrounds it (the scene's bounds), without it the box
  // touches the image's edges (a view window given in the scene).
  double bounds_min[2] = {0, 0}, bounds_max[2] = {1, 1};
  bool fit_margin = true;
};

struct FrameData {
  std::span<const double> fluid_xy;          // x0, y0, x1, y1, ... [m]
  std::span<const float> fluid_value;        // the coloured field, one per fluid particle
  std::span<const double> boundary_xy;
  std::span<const std::uint8_t> boundary_moving;  // 1: part of a moving object (may be empty)
  double diameter = 0;                       // disc diameter [m] (the particle spacing)
  double lo = 0, hi = 1;                     // colour range of fluid_value
  std::string overlay;                       // text of the overlay line (shown when enabled)
};

// Where things go in the image.
struct FrameLayout {
  ViewWindow view;
  int scale = 1;                 // font pixel size
  int bar_x = 0, bar_y = 0, bar_w = 0, bar_h = 0;
  double pixels_per_metre = 1;
};
FrameLayout fit_layout(const FrameSettings& s);

// Milliseconds spent in each part of the last frame.
struct FrameTimings {
  double draw = 0, read = 0, annotate = 0;
};

class FrameRenderer {
 public:
  explicit FrameRenderer(const FrameSettings& s);
  const std::string& description() const { return gl_.description(); }
  const FrameLayout& layout() const { return layout_; }
  // Renders into `out` (resized as needed).
  void render(const FrameData& d, Image& out);
  const FrameTimings& timings() const { return timings_; }

 private:
  FrameSettings s_;
  FrameLayout layout_;
  Colormap cmap_;
  GlRenderer gl_;
  std::vector<Rgb> fluid_rgb_, boundary_rgb_;
  FrameTimings timings_;
};

// Short tick label (at most 7 characters), e.g. "0.25", "1200", "1.5e+04".
std::string tick_label(double v);

// A colorbar's bar at (x, y), w x h pixels, top = hi, with its frame and five labelled
// ticks at its right (font scale s). Frames and montages draw their colorbars with it.
void draw_colorbar_bar(Image& img, int x, int y, int w, int h, int s, const Colormap& cmap, double lo, double hi);

}  // namespace sluice::render
