#pragma once
// A select between two doubles that GCC cannot turn into a branch. Without SSE4.1's
// blendv (baseline x86-64), GCC compiles `c ? a : b` on doubles to a conditional jump,
// and in the pair loops c (near or far on the kernel, approaching or receding) is random:
// about one misprediction in every second pair. Masks give the same bits as the branch.
#include <bit>
#include <cstdint>

namespace sluice {

inline double select(bool c, double a, double b) {
  const std::uint64_t mask = std::uint64_t{0} - static_cast<std::uint64_t>(c);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) | (std::bit_cast<std::uint64_t>(b) & ~mask));
}

}  // namespace sluice
