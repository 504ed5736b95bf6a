#pragma once
// Colormaps as 256-entry RGB tables, and the mapping of a scalar field to colours.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sluice::render {

enum class ColormapName { spectrum, viridis, turbo };

// "spectrum" | "viridis" | "turbo"; nullopt for anything else.
std::optional<ColormapName> parse_colormap(const std::string& s);
const char* to_string(ColormapName c);

struct Rgb {
  std::uint8_t r, g, b;
};

class Colormap {
 public:
  explicit Colormap(ColormapName name);
  // Colour of t in [0, 1] (clamped; NaN maps to 0).
  Rgb at(double t) const;
  // Colours of values mapped linearly from [lo, hi] to [0, 1].
  void map(std::span<const float> values, double lo, double hi, std::vector<Rgb>& out) const;

 private:
  std::array<Rgb, 256> table_{};
};

}  // namespace sluice::render
