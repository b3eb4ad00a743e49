#pragma once
// Memory of one derivative f(t, y), so that asking again at exactly the same point costs no
// evaluation: the first-same-as-last stage of an FSAL pair, or the shared first stage of the full
// step and the first half step of step doubling.
#include "ode/ode_system.hpp"

namespace jellysim::ode {

class DerivativeCache {
 public:
  /// Copies the stored f into `f` when (system, t, y) equal the stored point exactly.
  bool lookup(const OdeSystem& system, double t, const Vector& y, Vector& f) const;
  void store(const OdeSystem& system, double t, const Vector& y, const Vector& f);
  /// f(t, y) from memory when possible, otherwise evaluated and stored.
  void evaluate(const OdeSystem& system, double t, const Vector& y, Vector& f);
  void clear() { system_ = nullptr; }

 private:
  const OdeSystem* system_ = nullptr;
  double t_ = 0.0;
  Vector y_, f_;
};

}  // namespace jellysim::ode
