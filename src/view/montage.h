#pragma once
// Snapshot grids (the thesis' Figures 2 and 8): rendered cells of equal size in rows,
// each with a label band above it, an optional title, and one colorbar shared by every
// cell at the right. Pure image work on the CPU (no GL), so it is tested without EGL.
#include <optional>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "render/image.h"

namespace sluice::view {

struct MontageCell {
  render::Image image;
  std::vector<std::string> labels;  // lines of the band above the cell, e.g. "t = 0.40 s"
};

// One colour scale for every cell: cells are only comparable when they share it.
struct MontageColorbar {
  render::ColormapName colormap = render::ColormapName::spectrum;
  double lo = 0, hi = 1;
  std::string label;  // e.g. "pressure [Pa·m]"
};

// Where everything goes, from the cell size and count alone, so that tests (and anyone
// cropping a cell out again) know the exact pixel positions.
struct MontageLayout {
  int scale = 1;  // spacing unit (labels are 10 + 4 * scale pixels high)
  int columns = 1, rows = 1;
  int cell_w = 0, cell_h = 0;
  int margin = 0, gap = 0;
  int title_h = 0;                                 // band of the title at the top (0 without a title)
  int band_h = 0;                                  // label band above each cell
  int bar_x = 0, bar_y = 0, bar_w = 0, bar_h = 0;  // colorbar (bar_w == 0: none)
  int width = 0, height = 0;
  // Top-left corner of cell `i` (row-major) inside the montage.
  int cell_x(int i) const { return margin + (i % columns) * (cell_w + gap); }
  int cell_y(int i) const { return margin + title_h + (i / columns) * (band_h + cell_h + gap) + band_h; }
};

// Throws std::invalid_argument for count < 1 or columns < 1.
MontageLayout montage_layout(int cell_w, int cell_h, int count, int columns, int label_lines, bool title,
                             const std::optional<MontageColorbar>& colorbar);

// The cells in a grid of `columns` (fewer when there are fewer cells), row-major, on
// white. Throws std::invalid_argument for no cells, columns < 1, or cells of different
// sizes (the message names the first cell that differs and both sizes).
render::Image compose_montage(const std::vector<MontageCell>& cells, int columns, const std::string& title = "",
                              const std::optional<MontageColorbar>& colorbar = std::nullopt);

}  // namespace sluice::view
