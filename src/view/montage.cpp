#include "view/montage.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/font.h"
#include "render/frame.h"

namespace sluice::view {

using namespace sluice::render;

namespace {

constexpr Rgb kBackground{255, 255, 255};
constexpr Rgb kInk{25, 25, 25};

std::string size_text(const Image& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

// The spacing unit grows with the cells, as the renderer's labels do with the frame, so
// labels stay readable at any cell size: 2 for 480x270 cells, at most 4. Narrow cells
// keep it small enough for a label like "boundary_pressure = extrapolation" to fit.
int font_scale(int cell_w, int cell_h) { return std::clamp(std::min(cell_h / 135, cell_w / 240), 1, 4); }
// Pixel height of the labels and ticks: 18 px at scale 2 (480x270 cells), 14 px (still
// readable) at 1.
int text_px(int s) { return 10 + 4 * s; }
int title_px(int s) { return text_px(s) * 4 / 3; }

int line_height(int s) { return render::line_height(text_px(s)) + s; }

int colorbar_strip_width(int s) { return colorbar_width(text_px(s), 8 * s); }

// `text` shortened with ".." until it fits `width` pixels: a long label must not run
// into the neighbouring cell's band. Labels lose their start ("..PRESSURE = ZERO"), since
// their end (the value) is what tells cells apart; a title loses its end.
enum class Cut { start, end };
std::string fit_text(std::string text, int width, int px, Cut cut) {
  if (text_width(text, px) <= width) return text;
  // Cut whole UTF-8 characters (never a continuation byte alone).
  auto drop = [&] {
    if (cut == Cut::end) {
      do text.pop_back();
      while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80);
      if (!text.empty() && static_cast<unsigned char>(text.back()) >= 0xC0) text.pop_back();
    } else {
      do text.erase(0, 1);
      while (!text.empty() && (static_cast<unsigned char>(text.front()) & 0xC0) == 0x80);
    }
  };
  while (!text.empty() && text_width(cut == Cut::end ? text + ".." : ".." + text, px) > width) drop();
  return cut == Cut::end ? text + ".." : ".." + text;
}

void draw_colorbar(Image& img, const MontageLayout& L, const MontageColorbar& c) {
  const int s = L.scale, px = text_px(s);
  render::draw_colorbar_bar(img, L.bar_x, L.bar_y, L.bar_w, L.bar_h, px, Colormap(c.colormap), c.lo, c.hi);
  // The field's name in the band above the bar, as each cell's labels are above the
  // cell; smaller when it is wider than the strip (the layout never depends on it).
  const int room = L.width - L.bar_x - L.margin / 2;
  // A third of a line clear of the top tick's label, which is centred on the bar's top.
  draw_text(img, L.bar_x, L.bar_y - line_height(s) - px / 3, c.label, fit_text_size(c.label, px, room), kInk);
}

void check_cells(const std::vector<MontageCell>& cells) {
  if (cells.empty()) throw std::invalid_argument("compose_montage: no cells to arrange (need at least one)");
  const Image& first = cells.front().image;
  if (first.width < 1 || first.height < 1)
    throw std::invalid_argument("compose_montage: cell 0 is empty (" + size_text(first) + ")");
  for (size_t i = 1; i < cells.size(); ++i)
    if (cells[i].image.width != first.width || cells[i].image.height != first.height)
      throw std::invalid_argument("compose_montage: cell " + std::to_string(i) + " is " + size_text(cells[i].image) +
                                  " but cell 0 is " + size_text(first) + "; all cells must have the same size");
}

}  // namespace

MontageLayout montage_layout(int cell_w, int cell_h, int count, int columns, int label_lines, bool title,
                             const std::optional<MontageColorbar>& colorbar) {
  if (count < 1) throw std::invalid_argument("compose_montage: no cells to arrange (need at least one)");
  if (columns < 1) throw std::invalid_argument("compose_montage: columns must be >= 1, got " + std::to_string(columns));
  MontageLayout L;
  L.scale = font_scale(cell_w, cell_h);
  const int s = L.scale;
  L.columns = std::min(columns, count);  // no empty columns when there are fewer cells
  L.rows = (count + L.columns - 1) / L.columns;
  L.cell_w = cell_w;
  L.cell_h = cell_h;
  L.margin = 8 * s;
  L.gap = 8 * s;
  L.title_h = title ? render::line_height(title_px(s)) + 6 * s : 0;
  // At least one line, so that the colorbar's name has a band even without cell labels.
  L.band_h = std::max(1, label_lines) * line_height(s) + 2 * s;
  const int grid_w = L.columns * cell_w + (L.columns - 1) * L.gap;
  const int grid_h = L.rows * (L.band_h + cell_h) + (L.rows - 1) * L.gap;
  L.width = L.margin + grid_w + L.margin;
  L.height = L.margin + L.title_h + grid_h + L.margin;
  if (colorbar) {
    // Beside the grid, from the top of the first row's cells to the bottom of the last's.
    L.bar_x = L.margin + grid_w + 2 * L.gap;
    L.bar_y = L.margin + L.title_h + L.band_h;
    L.bar_w = 8 * s;
    L.bar_h = grid_h - L.band_h;
    L.width = L.bar_x + colorbar_strip_width(s) + L.margin;
  }
  return L;
}

Image compose_montage(const std::vector<MontageCell>& cells, int columns, const std::string& title,
                      const std::optional<MontageColorbar>& colorbar) {
  if (columns < 1) throw std::invalid_argument("compose_montage: columns must be >= 1, got " + std::to_string(columns));
  check_cells(cells);
  size_t lines = 0;
  for (const MontageCell& c : cells) lines = std::max(lines, c.labels.size());
  const MontageLayout L =
      montage_layout(cells.front().image.width, cells.front().image.height, static_cast<int>(cells.size()), columns,
                     static_cast<int>(lines), !title.empty(), colorbar);
  const int s = L.scale;
  Image out(L.width, L.height);
  fill_rect(out, 0, 0, out.width, out.height, kBackground);
  if (!title.empty()) {
    const int ts = title_px(s);
    const std::string text = fit_text(title, out.width - 2 * L.margin, ts, Cut::end);
    draw_text(out, (out.width - text_width(text, ts)) / 2, L.margin, text, ts, kInk);
  }
  for (size_t i = 0; i < cells.size(); ++i) {
    const int x = L.cell_x(static_cast<int>(i)), y = L.cell_y(static_cast<int>(i));
    const Image& img = cells[i].image;
    for (int row = 0; row < img.height; ++row)
      std::copy_n(img.at(0, row), static_cast<size_t>(img.width) * 3, out.at(x, y + row));
    // Lines from the top of the band; the last one sits just above the cell.
    int ty = y - L.band_h + s;
    for (const std::string& line : cells[i].labels) {
      draw_text(out, x, ty, fit_text(line, L.cell_w, text_px(s), Cut::start), text_px(s), kInk);
      ty += line_height(s);
    }
  }
  if (colorbar) draw_colorbar(out, L, *colorbar);
  return out;
}

}  // namespace sluice::view
