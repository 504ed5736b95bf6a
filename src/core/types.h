#pragma once
// Basic numeric types shared by the whole simulation library.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace sluice {

using Vec2 = Eigen::Vector2d;
// Single precision only where memory traffic decides the speed (cached kernel gradients).
using Vec2f = Eigen::Vector2f;
using Index = std::int32_t;

}  // namespace sluice
