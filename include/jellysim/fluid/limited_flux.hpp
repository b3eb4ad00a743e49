#pragma once
// The limited face values and fluxes of the Eulerian solvers' second-order convection (issue 20),
// shared by the 2D solver and the 3D one (fluid3d).
#include <algorithm>

#include "jellysim/fluid/schemes.hpp"

namespace jellysim::fluid {

// Limited value on the face between the upwind sample `up` and the downwind one `down`, with
// `far` one further upwind: up + ½ψ(r)(down − up), r = (up − far)/(down − up) (Hundsdorfer &
// Verwer 2003, §III.1). ψ = 0 where the data have an extremum (r ≤ 0): first-order upwind.
template <ConvectionScheme S>
inline double limited_face_value(double far, double up, double down) {
  const double num = up - far;
  const double den = down - up;
  if (!(num * den > 0.0)) return up;
  if constexpr (S == ConvectionScheme::van_leer) {
    return up + num * den / (num + den);  // ½ψ(r)·den with ψ(r) = 2r/(1 + r)
  } else {
    const double r = num / den;  // Koren: ψ(r) = max(0, min(2r, (1 + 2r)/3, 2))
    return up + 0.5 * std::min({2.0 * r, (1.0 + 2.0 * r) / 3.0, 2.0}) * den;
  }
}

// Flux carrier·q through a face between samples q_minus and q_plus (q_far_minus before q_minus,
// q_far_plus after q_plus), q taken from the upwind side.
template <ConvectionScheme S>
inline double limited_flux(double carrier, double q_far_minus, double q_minus, double q_plus, double q_far_plus) {
  return carrier >= 0.0 ? carrier * limited_face_value<S>(q_far_minus, q_minus, q_plus)
                        : carrier * limited_face_value<S>(q_far_plus, q_plus, q_minus);
}

}  // namespace jellysim::fluid
