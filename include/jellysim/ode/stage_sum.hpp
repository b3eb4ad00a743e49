#pragma once
// The state of a Runge–Kutta stage, y + h Σ_j w_j k_j (thesis eq. 2.38), formed in one pass over the
// entries instead of one pass per term: the stage sums are memory-bound, and a parallel system
// forms its own entries of them inside its evaluation (OdeSystem::stage_derivative).
#include "jellysim/ode/ode_system.hpp"

#include <span>

namespace jellysim::ode {

/// out[start, start + length) = y + h Σ_j weights[j] k[j] on that segment: terms with a zero weight
/// skipped, the others added in j order, each entry rounded exactly as by `out = y` followed by
/// `out += (h * weights[j]) * k[j]` for each term (the same operations in the same order). `out`
/// must have at least start + length entries and must not share storage with y or the k[j].
void form_stage_segment(const Vector& y, double h, std::span<const double> weights, std::span<const Vector> k,
                        Vector& out, Eigen::Index start, Eigen::Index length);

/// out (resized to the size of the k[j]) = h Σ_j weights[j] k[j], rounded as `out = 0` followed by
/// the term-by-term additions (an embedded error estimate, eq. 2.40).
void form_weighted_sum(double h, std::span<const double> weights, std::span<const Vector> k, Vector& out);

/// The whole vector: out (resized) = y + h Σ_j weights[j] k[j].
void form_stage_state(const Vector& y, double h, std::span<const double> weights, std::span<const Vector> k,
                      Vector& out);

}  // namespace jellysim::ode
