#pragma once
// A select between two doubles that GCC cannot turn into a branch. Without SSE4.1's
// blendv (baseline x86-64), GCC compiles `c ? a : b` on doubles to a conditional jump;
// where c is random in a pair loop (a pair approaching or receding), that mispredicts in
// about every second pair. Masks give the same bits as the branch. Worth it only where
// neither side costs more than the misprediction (not where one side divides).
// (Not named select: POSIX's ::select is declared by <sys/select.h>.)
#include <bit>
#include <cstdint>

namespace sluice {

inline double mask_select(bool c, double a, double b) {
  const std::uint64_t mask = std::uint64_t{0} - static_cast<std::uint64_t>(c);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) | (std::bit_cast<std::uint64_t>(b) & ~mask));
}

}  // namespace sluice
