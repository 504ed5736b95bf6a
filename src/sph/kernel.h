#pragma once
// SPH kernels in 2D with support radius 2h (q = |r| / h), chosen by solver.kernel.
//
// Cubic spline, thesis section 2.2.2 (the reference):
//   W(r, h) = alpha_2 * { (2-q)^3 - 4(1-q)^3  for 0 <= q < 1
//                        (2-q)^3             for 1 <= q < 2
//                        0                   for q >= 2 },
//   alpha_2 = 5 / (14 pi h^2).
// (The thesis prints "+ 4(1-q)^3"; the standard spline that integrates to one and is
// smooth at q = 1 has the minus sign, which the kernel test checks.)
//
// Wendland C2 (Wendland 1995; the thesis has none; Dehnen & Aly 2012 for its use in SPH:
// no pairing instability, so a stretched lattice keeps its kernel sum at wider supports):
//   W(r, h) = alpha_w (1 - q/2)^4 (1 + 2q)  for q < 2,  alpha_w = 7 / (4 pi h^2),
//   dW/dr / r = -5 alpha_w (1 - q/2)^3 / h^2 (no division, finite at r = 0).
#include <cmath>

#include "core/lanes.h"
#include "core/types.h"

namespace sluice {

enum class KernelKind { CubicSpline, WendlandC2 };

class Kernel2D {
 public:
  explicit Kernel2D(double h, KernelKind kind = KernelKind::CubicSpline)
      : kind_(kind),
        h_(h),
        inv_h_(1.0 / h),
        alpha_(kind == KernelKind::CubicSpline ? 5.0 / (14.0 * M_PI * h * h) : 7.0 / (4.0 * M_PI * h * h)),
        support_(2.0 * h) {}

  KernelKind kind() const { return kind_; }
  double h() const { return h_; }
  double support() const { return support_; }

  // W(|r|) for a distance r >= 0.
  double W(double r) const {
    const double q = r * inv_h_;
    if (q >= 2.0) return 0.0;
    if (kind_ == KernelKind::WendlandC2) {
      const double c = 1.0 - 0.5 * q, c3 = c * c * c;
      return alpha_ * c3 * c * (1.0 + 2.0 * q);  // as in eval, to the bit
    }
    const double a = 2.0 - q;
    double w = a * a * a;
    if (q < 1.0) {
      const double b = 1.0 - q;
      w -= 4.0 * b * b * b;
    }
    return alpha_ * w;
  }
  double W(const Vec2& r) const { return W(r.norm()); }

  // dW/dr divided by r: gradW(r_vec) = r_vec * dWdr_over_r(|r|). Zero at r = 0.
  double dWdr_over_r(double r) const {
    const double q = r * inv_h_;
    if (q >= 2.0 || r <= 0.0) return 0.0;
    if (kind_ == KernelKind::WendlandC2) {
      const double c = 1.0 - 0.5 * q, c3 = c * c * c;
      return -5.0 * alpha_ * inv_h_ * inv_h_ * c3;  // as in eval, to the bit
    }
    const double a = 2.0 - q;
    double d = -3.0 * a * a;
    if (q < 1.0) {
      const double b = 1.0 - q;
      d += 12.0 * b * b;
    }
    return alpha_ * d * inv_h_ / r;
  }
  // Gradient with respect to x_i of W(x_i - x_j): grad W(x_ij).
  Vec2 gradW(const Vec2& r) const { return r * dWdr_over_r(r.norm()); }

  // W(r) and dW/dr / r together, sharing q (the neighbour pass needs both). Both
  // pieces are computed and one selected: which one a pair needs is random in the
  // neighbour order, and a select gives the bits of the branch without its mispredictions.
  void eval(double r, double& w, double& dw_over_r) const {
    const double q = r * inv_h_;
    if (q >= 2.0) {
      w = dw_over_r = 0.0;
      return;
    }
    if (kind_ == KernelKind::WendlandC2) {  // one branch for the whole run: predicted
      const double c = 1.0 - 0.5 * q, c3 = c * c * c;
      w = alpha_ * c3 * c * (1.0 + 2.0 * q);
      dw_over_r = -5.0 * alpha_ * inv_h_ * inv_h_ * c3;
      return;
    }
    const bool near = q < 1.0;
    const double a = 2.0 - q, b = 1.0 - q;
    const double w_near = alpha_ * (a * a * a - 4.0 * b * b * b);
    // (-3 a^2 + 12 b^2) / q = -12 + 9 q: no division, and finite at r = 0.
    const double d_near = alpha_ * inv_h_ * inv_h_ * (9.0 * q - 12.0);
    const double w_far = alpha_ * a * a * a;
    const double d_far = alpha_ * inv_h_ * (-3.0 * a * a) / (near ? 1.0 : r);
    w = near ? w_near : w_far;
    dw_over_r = near ? d_near : d_far;
  }

  // eval for two pairs at once, each lane to the bit of eval's: the same operations in
  // the same order, the pieces selected by masks. Both pieces are computed in both lanes,
  // and the far piece's division and the square root before it take one instruction for
  // two pairs.
  void eval2(Double2 r, Double2& w, Double2& dw_over_r) const {
    const Double2 q = r * inv_h_;
    const Mask2 inside = q < 2.0;
    if (kind_ == KernelKind::WendlandC2) {
      const Double2 c = 1.0 - 0.5 * q, c3 = c * c * c;
      w = select_lanes(inside, alpha_ * c3 * c * (1.0 + 2.0 * q), splat(0.0));
      dw_over_r = select_lanes(inside, -5.0 * alpha_ * inv_h_ * inv_h_ * c3, splat(0.0));
      return;
    }
    const Mask2 near = q < 1.0;
    const Double2 a = 2.0 - q, b = 1.0 - q;
    const Double2 w_near = alpha_ * (a * a * a - 4.0 * b * b * b);
    const Double2 d_near = alpha_ * inv_h_ * inv_h_ * (9.0 * q - 12.0);
    const Double2 w_far = alpha_ * a * a * a;
    const Double2 d_far = alpha_ * inv_h_ * (-3.0 * a * a) / select_lanes(near, splat(1.0), r);
    w = select_lanes(inside, select_lanes(near, w_near, w_far), splat(0.0));
    dw_over_r = select_lanes(inside, select_lanes(near, d_near, d_far), splat(0.0));
  }

 private:
  KernelKind kind_;
  double h_, inv_h_, alpha_, support_;
};

}  // namespace sluice
