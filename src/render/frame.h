#pragma once
// One frame of a particle scene: the view fitted to the scene's bounds, fluid discs
// coloured by a field through a colormap, boundary discs in their objects' colours, a
// colorbar with round ticks beside the scene and an optional band at the top with a
// title line and an overlay line. Solver-agnostic: it takes arrays.
//
// The layout comes from fixed bands computed from the image size, the scene's bounds
// and which bands are on, never from the labels' text: frames of one scene line up
// across colour fields and across the overlay's digits.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "render/gl_renderer.h"

namespace sluice::render {

struct FrameSettings {
  int width = 1280, height = 720;
  int msaa = 0;  // 0 or 4
  EglPlatform egl = EglPlatform::automatic;
  ColormapName colormap = ColormapName::spectrum;
  std::string field_label = "CFL";  // title above the colorbar
  bool colorbar = true;
  bool overlay = true;  // the overlay line's row in the top band
  std::string title;    // a title row in the top band (none when empty)
  // The world box to show, centred with the aspect ratio kept; with fit_margin a margin
  // of a few percent of the image surrounds it (the scene's bounds), without it the box
  // touches the image's edges (a view window given in the scene).
  double bounds_min[2] = {0, 0}, bounds_max[2] = {1, 1};
  bool fit_margin = true;
  Rgb background{255, 255, 255};
  double particle_scale = 1.0;  // disc diameter as a multiple of the spacing
};

struct FrameData {
  std::span<const double> fluid_xy;    // x0, y0, x1, y1, ... [m]
  std::span<const float> fluid_value;  // the coloured field, one per fluid particle
  std::span<const double> boundary_xy;
  std::span<const Rgb> boundary_rgb;  // one per boundary sample (may be empty: grey)
  double diameter = 0;                // disc diameter [m] (the particle spacing)
  double lo = 0, hi = 1;              // colour range of fluid_value
  std::string overlay;                // text of the overlay line (shown when enabled)
};

// Where things go in the image.
struct FrameLayout {
  ViewWindow view;
  int text_px = 10;              // pixel height of every label
  int pad = 2;                   // spacing unit around labels
  int band_h = 0;                // top band (title and overlay rows; 0 without either)
  int strip_x = 0, strip_w = 0;  // the colorbar's own columns (strip_w == 0: none)
  int bar_x = 0, bar_y = 0, bar_w = 0, bar_h = 0;
  int scene_x0 = 0, scene_y0 = 0, scene_x1 = 0, scene_y1 = 0;  // the bounds in pixels
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

// Round tick values in [lo, hi]: multiples of a step of 1, 2 or 5 times a power of ten,
// about `target` of them (at least two where the range allows).
std::vector<double> nice_ticks(double lo, double hi, int target = 5);
// The step between nice_ticks(lo, hi, target) (the power of ten times 1, 2 or 5).
double nice_step(double lo, double hi, int target = 5);
// A tick's label with as many decimals as the step needs: "0.25", "1200", "1.5e+04".
std::string tick_label(double v, double step);

// A colorbar's bar at (x, y), w x h pixels, top = hi, with its frame and round labelled
// ticks at its right (labels px high). Frames and montages draw their colorbars with it.
void draw_colorbar_bar(Image& img, int x, int y, int w, int h, int px, const Colormap& cmap, double lo, double hi,
                       Rgb ink = {25, 25, 25});
// Near-black labels on a light background, near-white on a dark one (--background).
Rgb ink_on(Rgb background);
// Columns the tick marks and labels need right of the bar at `px`, whatever the values.
int colorbar_label_width(int px);
// Columns the colorbar needs from the bar's left edge at `px`: its ticks and labels, or
// the widest field name the program gives it ("density error [%]"), whichever is
// wider; longer names are drawn smaller. Never the actual name: fields line up.
int colorbar_width(int px, int bar_w);

}  // namespace sluice::render
