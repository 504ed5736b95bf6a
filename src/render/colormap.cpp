// Colormap tables, built once from closed forms:
// - spectrum: the thesis' velocity colouring, blue -> cyan -> green -> yellow -> red,
//   linear between five equally spaced stops;
// - viridis: a degree-6 polynomial fit per channel of matplotlib's viridis;
// - turbo: the degree-5 polynomial approximation published with Google's Turbo map.
#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace sluice::render {

std::optional<ColormapName> parse_colormap(const std::string& s) {
  if (s == "spectrum") return ColormapName::spectrum;
  if (s == "viridis") return ColormapName::viridis;
  if (s == "turbo") return ColormapName::turbo;
  return std::nullopt;
}

const char* to_string(ColormapName c) {
  switch (c) {
    case ColormapName::spectrum:
      return "spectrum";
    case ColormapName::viridis:
      return "viridis";
    case ColormapName::turbo:
      return "turbo";
  }
  return "?";
}

namespace {

struct Rgbd {
  double r, g, b;
};

Rgbd spectrum(double t) {
  static const Rgbd stops[5] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  const double s = t * 4.0;
  const int k = std::min(3, static_cast<int>(s));
  const double f = s - k;
  const Rgbd& a = stops[k];
  const Rgbd& b = stops[k + 1];
  return {a.r + (b.r - a.r) * f, a.g + (b.g - a.g) * f, a.b + (b.b - a.b) * f};
}

// Horner evaluation of sum c[k] t^k.
template <size_t N>
double poly(const double (&c)[N], double t) {
  double v = 0;
  for (size_t k = N; k-- > 0;) v = v * t + c[k];
  return v;
}

Rgbd viridis(double t) {
  static const double r[7] = {0.2777273272234177, 0.1050930431085774, -0.3308618287255563, -4.634230498983486,
                              6.228269936347081,  4.776384997670288,  -5.435455855934631};
  static const double g[7] = {0.005407344544966578, 1.404613529898575,  0.214847559468213, -5.799100973351585,
                              14.17993336680509,    -13.74514537774601, 4.645852612178535};
  static const double b[7] = {0.3340998053353061, 1.384590162594685,  0.09509516302823659, -19.33244095627987,
                              56.69055260068105,  -65.35303263337234, 26.3124352495832};
  return {poly(r, t), poly(g, t), poly(b, t)};
}

Rgbd turbo(double t) {
  static const double r[6] = {0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943};
  static const double g[6] = {0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604};
  static const double b[6] = {0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973};
  return {poly(r, t), poly(g, t), poly(b, t)};
}

std::uint8_t to_byte(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

}  // namespace

Colormap::Colormap(ColormapName name) {
  for (int i = 0; i < 256; ++i) {
    const double t = i / 255.0;
    const Rgbd c = name == ColormapName::spectrum ? spectrum(t) : name == ColormapName::viridis ? viridis(t) : turbo(t);
    table_[static_cast<size_t>(i)] = {to_byte(c.r), to_byte(c.g), to_byte(c.b)};
  }
}

Rgb Colormap::at(double t) const {
  if (!(t > 0)) return table_[0];  // also NaN
  if (t >= 1) return table_[255];
  return table_[static_cast<size_t>(std::lround(t * 255.0))];
}

void Colormap::map(std::span<const float> values, double lo, double hi, std::vector<Rgb>& out) const {
  out.resize(values.size());
  const double scale = hi > lo ? 1.0 / (hi - lo) : 0.0;
  for (size_t i = 0; i < values.size(); ++i) out[i] = at((values[i] - lo) * scale);
}

}  // namespace sluice::render
