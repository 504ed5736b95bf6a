// `sluice montage` and compose_montage(): the grid of synthetic solid-colour cells pixel
// by pixel (positions, label bands, the shared colorbar, the errors), then the program
// itself on a tiny scene. Only RenderMontage.* needs EGL (the sanitizer pass of CI
// runs no test labelled render, and this whole binary is); the bad-input cases fail
// before any rendering.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "render/image.h"
#include "test_process.h"
#include "view/montage.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;
using namespace sluice::render;
using namespace sluice::view;

Image solid(int w, int h, Rgb c) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      img.at(x, y)[0] = c.r;
      img.at(x, y)[1] = c.g;
      img.at(x, y)[2] = c.b;
    }
  return img;
}

bool pixel_is(const Image& img, int x, int y, Rgb c) {
  const std::uint8_t* p = img.at(x, y);
  return p[0] == c.r && p[1] == c.g && p[2] == c.b;
}

// Pixels in the rectangle for which `pred` holds.
long count_pixels(const Image& img, int x0, int y0, int w, int h,
                  const std::function<bool(const std::uint8_t*)>& pred) {
  long n = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) n += pred(img.at(x, y));
  return n;
}

bool dark(const std::uint8_t* p) { return p[0] < 100 && p[1] < 100 && p[2] < 100; }
bool not_white(const std::uint8_t* p) { return p[0] != 255 || p[1] != 255 || p[2] != 255; }

const Rgb kColours[] = {{200, 30, 30}, {30, 200, 30}, {30, 30, 200}, {200, 200, 30}, {30, 200, 200}};

std::vector<MontageCell> solid_cells(int n, int w, int h) {
  std::vector<MontageCell> cells;
  for (int i = 0; i < n; ++i) cells.push_back({solid(w, h, kColours[i % 5]), {}});
  return cells;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Montage, CellsInRowMajorGridAtExactPositions) {
  // Five 20x10 cells in 2 columns: 3 rows, the last with one cell. At this size the
  // scale is 1: margin 8, gap 8, label band 17 (one 14 px line of 15 rows + 2) even
  // without labels.
  const Image m = compose_montage(solid_cells(5, 20, 10), 2);
  EXPECT_EQ(m.width, 8 + 20 + 8 + 20 + 8);
  EXPECT_EQ(m.height, 8 + 3 * (17 + 10) + 2 * 8 + 8);
  const MontageLayout L = montage_layout(20, 10, 5, 2, 0, false, std::nullopt);
  for (int i = 0; i < 5; ++i) {
    const int x = 8 + (i % 2) * 28, y = 8 + (i / 2) * 35 + 17;
    EXPECT_EQ(L.cell_x(i), x);
    EXPECT_EQ(L.cell_y(i), y);
    // Every pixel of the cell is its colour, and the pixels around it are background.
    EXPECT_EQ(count_pixels(m, x, y, 20, 10,
                           [&](const std::uint8_t* p) {
                             return p[0] == kColours[i].r && p[1] == kColours[i].g && p[2] == kColours[i].b;
                           }),
              200)
        << "cell " << i;
    EXPECT_TRUE(pixel_is(m, x - 1, y, {255, 255, 255})) << "cell " << i;
    EXPECT_TRUE(pixel_is(m, x + 20, y + 9, {255, 255, 255})) << "cell " << i;
    EXPECT_TRUE(pixel_is(m, x, y + 10, {255, 255, 255})) << "cell " << i;
  }
  // The sixth slot stays empty.
  EXPECT_EQ(count_pixels(m, L.cell_x(5), L.cell_y(5), 20, 10, not_white), 0);
  // More columns than cells: no empty columns.
  EXPECT_EQ(compose_montage(solid_cells(2, 20, 10), 4).width, 8 + 20 + 8 + 20 + 8);
}

TEST(Montage, LabelBandsHoldDarkText) {
  std::vector<MontageCell> cells = solid_cells(2, 200, 40);
  cells[0].labels = {"t = 0.40 s", "boundary_pressure = mirroring"};
  cells[1].labels = {"t = 0.80 s"};
  const Image m = compose_montage(cells, 2);
  const MontageLayout L = montage_layout(200, 40, 2, 2, 2, false, std::nullopt);
  ASSERT_EQ(m.width, L.width);
  ASSERT_EQ(m.height, L.height);
  EXPECT_EQ(L.band_h, 2 * 15 + 2);
  // First line in the band's upper half, second in its lower half, for cell 0.
  const int x0 = L.cell_x(0), top = L.cell_y(0) - L.band_h;
  EXPECT_GT(count_pixels(m, x0, top, 200, L.band_h / 2, dark), 20);
  EXPECT_GT(count_pixels(m, x0, top + L.band_h / 2, 200, L.band_h / 2, dark), 20);
  // Cell 1 has one line: its band's lower half is blank.
  const int x1 = L.cell_x(1);
  EXPECT_GT(count_pixels(m, x1, top, 200, L.band_h / 2, dark), 20);
  EXPECT_EQ(count_pixels(m, x1, top + L.band_h / 2, 200, L.band_h / 2, not_white), 0);
  // The label's text is the ink colour, not the cell's: the cell itself is untouched.
  EXPECT_EQ(count_pixels(m, x0, L.cell_y(0), 200, 40, dark), 0);
}

TEST(Montage, LongLabelIsCutToItsCell) {
  std::vector<MontageCell> cells = solid_cells(2, 30, 10);
  cells[0].labels = {"a label far wider than the cell"};
  const Image m = compose_montage(cells, 2);
  const MontageLayout L = montage_layout(30, 10, 2, 2, 1, false, std::nullopt);
  // Nothing in the gap between cell 0's band and cell 1's band.
  EXPECT_EQ(count_pixels(m, L.cell_x(0) + 30, L.cell_y(0) - L.band_h, L.gap, L.band_h, not_white), 0);
}

TEST(Montage, SharedColorbarWhenRequested) {
  const MontageColorbar bar{ColormapName::viridis, 0, 4000, "pressure [Pa\u00b7m]"};
  const Image without = compose_montage(solid_cells(4, 60, 30), 2);
  const Image with = compose_montage(solid_cells(4, 60, 30), 2, "", bar);
  const MontageLayout L = montage_layout(60, 30, 4, 2, 0, false, bar);
  ASSERT_EQ(with.width, L.width);
  ASSERT_EQ(with.height, without.height);
  EXPECT_GT(with.width, without.width);
  // Right of the grid: nothing without a colorbar.
  const int grid_right = L.cell_x(1) + 60;
  EXPECT_EQ(count_pixels(without, grid_right, 0, without.width - grid_right, without.height, not_white), 0);
  // The bar runs from the colormap's top colour at the top to its bottom colour at the
  // bottom, over the grid's cell rows.
  ASSERT_GT(L.bar_w, 0);
  EXPECT_EQ(L.bar_y, L.cell_y(0));
  EXPECT_EQ(L.bar_y + L.bar_h, L.cell_y(2) + 30);
  const Colormap cmap(ColormapName::viridis);
  const int cx = L.bar_x + L.bar_w / 2;
  EXPECT_TRUE(pixel_is(with, cx, L.bar_y, cmap.at(1.0 - 0.5 / L.bar_h)));
  // (1 - (h - 0.5) / h, as the bar computes it: 0.5 / h may round to the next level.)
  EXPECT_TRUE(pixel_is(with, cx, L.bar_y + L.bar_h - 1, cmap.at(1.0 - (L.bar_h - 0.5) / L.bar_h)));
  // Tick labels right of the bar and the field's name above it.
  EXPECT_GT(count_pixels(with, L.bar_x + L.bar_w + 1, L.bar_y, with.width - L.bar_x - L.bar_w - 1, L.bar_h, dark), 50);
  EXPECT_GT(count_pixels(with, L.bar_x, L.bar_y - L.band_h, with.width - L.bar_x, L.band_h, dark), 50);
  // The cells are where they were.
  EXPECT_TRUE(pixel_is(with, L.cell_x(3), L.cell_y(3), kColours[3]));
}

TEST(Montage, TitleShiftsTheGridDown) {
  const Image m = compose_montage(solid_cells(2, 60, 30), 2, "Dam break");
  const MontageLayout L = montage_layout(60, 30, 2, 2, 0, true, std::nullopt);
  ASSERT_GT(L.title_h, 0);
  ASSERT_EQ(m.height, L.height);
  EXPECT_GT(count_pixels(m, 0, 0, m.width, L.margin + L.title_h, dark), 30);
  EXPECT_TRUE(pixel_is(m, L.cell_x(0), L.cell_y(0), kColours[0]));
  EXPECT_TRUE(pixel_is(m, L.cell_x(0), L.cell_y(0) - 1, {255, 255, 255}));
}

TEST(Montage, ErrorsSayWhatIsWrong) {
  EXPECT_NE(error_of([] { compose_montage({}, 2); }).find("no cells"), std::string::npos);
  EXPECT_NE(error_of([] { compose_montage(solid_cells(2, 20, 10), 0); }).find("columns must be >= 1, got 0"),
            std::string::npos);
  std::vector<MontageCell> cells = solid_cells(3, 20, 10);
  cells[2].image = solid(30, 10, kColours[0]);
  const std::string msg = error_of([&] { compose_montage(cells, 2); });
  EXPECT_NE(msg.find("cell 2 is 30x10 but cell 0 is 20x10"), std::string::npos) << msg;
}

// --- the program ---------------------------------------------------------------------------

const std::string kColumn = std::string(SLUICE_SOURCE_DIR) + "/scenes/column.json";

std::vector<std::string> tiny_montage(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"montage", kColumn, "--set", "spacing=0.04", "--set", "time.duration=0.2"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

Image crop(const Image& img, int x0, int y0, int w, int h) {
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) std::copy_n(img.at(x0 + x, y0 + y), 3, out.at(x, y));
  return out;
}

TEST(RenderMontage, VaryGivesGridOfFourDistinctCells) {
  const test::CaseDir dir;
  const fs::path png = dir.work() / "m.png";
  const test::Result r =
      test::run_sluice(dir, tiny_montage({"--times", "0,0.1", "--vary", "solver.boundary_pressure=extrapolation,zero",
                                          "--cell", "160x90", "--color-by", "speed", "-o", png.string()}));
  ASSERT_EQ(r.status, 0) << r.err;
  const Image m = read_png(png.string());
  // Two variants x two times, variant-major: columns = the number of times; two label
  // lines per cell (time, variant); the shared colorbar named after the field.
  const MontageLayout L =
      montage_layout(160, 90, 4, 2, 2, false, MontageColorbar{ColormapName::spectrum, 0, 1, "speed [m/s]"});
  EXPECT_EQ(m.width, L.width);
  EXPECT_EQ(m.height, L.height);
  ASSERT_EQ(L.rows, 2);
  std::set<std::string> distinct_cells, distinct_with_band;
  for (int i = 0; i < 4; ++i) {
    const Image cell = crop(m, L.cell_x(i), L.cell_y(i), 160, 90);
    EXPECT_GT(count_pixels(cell, 0, 0, 160, 90, not_white), 500) << "cell " << i << " is blank";
    EXPECT_GT(count_pixels(m, L.cell_x(i), L.cell_y(i) - L.band_h, 160, L.band_h, dark), 40) << "cell " << i;
    distinct_cells.insert(std::string(cell.rgb.begin(), cell.rgb.end()));
    const Image with_band = crop(m, L.cell_x(i), L.cell_y(i) - L.band_h, 160, L.band_h + 90);
    distinct_with_band.insert(std::string(with_band.rgb.begin(), with_band.rgb.end()));
  }
  // Labelled cells all differ; the pictures differ except that both runs start alike.
  EXPECT_EQ(distinct_with_band.size(), 4u);
  EXPECT_GE(distinct_cells.size(), 3u);
  EXPECT_NE(crop(m, L.cell_x(0), L.cell_y(0), 160, 90).rgb, crop(m, L.cell_x(1), L.cell_y(1), 160, 90).rgb)
      << "t = 0 and t = 0.1 look the same";
  EXPECT_NE(r.err.find("wrote"), std::string::npos) << r.err;
}

// Bad input: one clear line, the right status, and no image.
void expect_refused(const std::vector<std::string>& extra, int status, const std::vector<std::string>& fragments) {
  const test::CaseDir dir;
  const fs::path png = dir.work() / "m.png";
  std::vector<std::string> args = extra;
  args.insert(args.end(), {"-o", png.string()});
  const test::Result r = test::run_sluice(dir, tiny_montage(args));
  EXPECT_EQ(r.status, status) << r.err;
  EXPECT_EQ(r.err.rfind("sluice:", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const std::string& f : fragments)
    EXPECT_NE(r.err.find(f), std::string::npos) << "missing '" << f << "': " << r.err;
  EXPECT_FALSE(fs::exists(png));
}

TEST(Montage, RefusesTimesAfterTheEnd) {
  expect_refused({"--times", "0,0.5"}, 1, {"--times 0,0.5", "0.5 s is after the scene's end", "time.duration = 0.2"});
}

TEST(Montage, RefusesDecreasingTimes) {
  expect_refused({"--times", "0.1,0.05"}, 1, {"--times 0.1,0.05", "strictly increasing", "0.05 follows 0.1"});
  expect_refused({"--times", "0,0.1,0.1"}, 1, {"strictly increasing"});
  expect_refused({"--times", "0,abc"}, 1, {"--times 0,abc", "expected simulated times"});
}

TEST(Montage, RefusesUnknownVaryKey) {
  expect_refused({"--times", "0,0.1", "--vary", "solver.boundary_presure=zero,mirroring"}, 2,
                 {"scene error", "boundary_presure", "unknown key"});
  expect_refused({"--times", "0,0.1", "--vary", "solver.boundary_pressure"}, 1, {"--vary", "KEY=V1,V2"});
}

TEST(Montage, RefusesZeroColumns) { expect_refused({"--times", "0,0.1", "--cols", "0"}, 1, {"--cols", "'0'"}); }

TEST(Montage, RefusesOutputInMissingFolder) {
  const test::CaseDir dir;
  const fs::path png = dir.work() / "no_such_folder" / "m.png";
  const test::Result r = test::run_sluice(dir, tiny_montage({"--times", "0,0.1", "-o", png.string()}));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("sluice: output error:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no_such_folder does not exist"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png.parent_path()));
}

}  // namespace
}  // namespace sluice
