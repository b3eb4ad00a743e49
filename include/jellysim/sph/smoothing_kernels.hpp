#pragma once
// The 2D SPH smoothing kernels of thesis §5.1.1, each normalised so that 2π ∫₀ʰ r W(r) dr = 1
// (eq. 5.13), with W, ∇W and ∇²W all zero at r = h. Distances in metres; W in 1/m².
//   poly6 (eq. 5.15):     W = 4/(π h⁸) (h² − r²)³            — density (eq. 5.5)
//   spiky (eq. 5.14):     W = 10/(π h⁵) (h − r)³              — pressure gradient (eq. 5.6)
//                         dW/dr = −30/(π h⁵) (h − r)²          (not the kernel itself!)
//   viscosity (eq. 5.19): W = 10/(9π h⁵) (−5h³ + 9hr² − 4r³ + 6h³ ln(h/r))
//                         ∇²W = 40/(π h⁵) (h − r)  (eq. 5.20, 2D polar Laplacian eq. 5.10)
#include "jellysim/math/vec2.hpp"

#include <cmath>
#include <numbers>

namespace jellysim::sph {

class Kernels {
 public:
  explicit Kernels(double h_m)
      : h_(h_m),
        h2_(h_m * h_m),
        poly6_(4.0 / (std::numbers::pi * std::pow(h_m, 8))),
        spiky_(10.0 / (std::numbers::pi * std::pow(h_m, 5))),
        viscosity_laplacian_(40.0 / (std::numbers::pi * std::pow(h_m, 5))) {}

  double h() const { return h_; }
  double h2() const { return h2_; }

  /// Eq. 5.15 from the squared distance (no square root needed); 0 outside the support.
  double poly6_r2(double r2) const {
    if (r2 >= h2_) return 0.0;
    const double d = h2_ - r2;
    return poly6_ * d * d * d;
  }
  double poly6(double r) const { return poly6_r2(r * r); }
  /// dW/dr of eq. 5.15: −24 r/(π h⁸) (h² − r²)².
  double poly6_derivative(double r) const {
    if (r >= h_) return 0.0;
    const double d = h2_ - r * r;
    return -6.0 * poly6_ * r * d * d;
  }

  /// Eq. 5.14.
  double spiky(double r) const {
    if (r >= h_) return 0.0;
    const double d = h_ - r;
    return spiky_ * d * d * d;
  }
  /// dW/dr of eq. 5.14: −30/(π h⁵) (h − r)².
  double spiky_derivative(double r) const {
    if (r >= h_) return 0.0;
    const double d = h_ - r;
    return -3.0 * spiky_ * d * d;
  }
  /// ∇W(x) = x̂ dW/dr (eq. 5.11) for the offset x = x_i − x_j with |x| = r > 0; zero at r = 0
  /// (the limit direction is undefined there; by symmetry the pair contributes nothing).
  Vec2 spiky_gradient(Vec2 offset, double r) const {
    if (r <= 0.0 || r >= h_) return {0.0, 0.0};
    return offset * (spiky_derivative(r) / r);
  }

  /// Eq. 5.19 (singular, but integrable, at r = 0).
  double viscosity(double r) const {
    if (r >= h_) return 0.0;
    const double h3 = h2_ * h_;
    return spiky_ / 9.0 * (-5.0 * h3 + 9.0 * h_ * r * r - 4.0 * r * r * r + 6.0 * h3 * std::log(h_ / r));
  }
  /// dW/dr of eq. 5.19: 10/(9π h⁵) (18 h r − 12 r² − 6 h³/r).
  double viscosity_derivative(double r) const {
    if (r >= h_) return 0.0;
    return spiky_ / 9.0 * (18.0 * h_ * r - 12.0 * r * r - 6.0 * h2_ * h_ / r);
  }
  /// Eq. 5.20.
  double viscosity_laplacian(double r) const { return r >= h_ ? 0.0 : viscosity_laplacian_ * (h_ - r); }

 private:
  double h_, h2_;
  double poly6_, spiky_, viscosity_laplacian_;
};

}  // namespace jellysim::sph
