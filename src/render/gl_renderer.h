#pragma once
// Draws particles as anti-aliased discs into an off-screen framebuffer (optionally
// 4x multisampled) and reads the pixels back. Knows nothing of solvers: it takes
// positions, colours and a disc diameter.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "render/colormap.h"
#include "render/egl.h"
#include "render/image.h"

namespace sluice::render {

// The world rectangle that covers the whole image (x to the right, y up).
struct ViewWindow {
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
};

class GlRenderer {
 public:
  // msaa: 0 (none) or 4. Throws RenderError (EGL, GL or framebuffer failures).
  GlRenderer(int width, int height, int msaa, EglPlatform platform);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  const std::string& description() const;
  int width() const { return width_; }
  int height() const { return height_; }

  void clear(Rgb background);
  // xy: x0, y0, x1, y1, ... in world units; one colour per disc; drawn in order.
  void draw_discs(const ViewWindow& view, double diameter, std::span<const double> xy, std::span<const Rgb> colors);
  // Blocks until the drawing is done (for timing).
  void finish();
  // Waits for the drawing and copies the frame into `out` (rows top to bottom).
  void read(Image& out);

 private:
  struct Gl;
  std::unique_ptr<EglContext> egl_;
  std::unique_ptr<Gl> gl_;
  int width_, height_, msaa_;
};

}  // namespace sluice::render
