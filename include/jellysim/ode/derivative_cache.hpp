#pragma once
// Memory of one derivative f(t, y), so that asking again at exactly the same point costs no
// evaluation: the first-same-as-last stage of an FSAL pair, or the shared first stage of the full
// step and the first half step of step doubling.
#include "jellysim/ode/ode_system.hpp"

namespace jellysim::ode {

class DerivativeCache {
 public:
  /// Copies the stored f into `f` when (system, t, y) equal the stored point exactly.
  bool lookup(const OdeSystem& system, double t, const Vector& y, Vector& f) const;
  void store(const OdeSystem& system, double t, const Vector& y, const Vector& f);
  /// As lookup(), but hands the stored f over by swapping it into `f` (no copy) and forgets it.
  bool take(const OdeSystem& system, double t, const Vector& y, Vector& f);
  /// As store(), but keeps f by swapping it in (no copy): `f` is left with unspecified contents.
  /// Moving vectors instead of copying them leaves every entry in the buffer, and so in the cache
  /// of the core, that wrote it (a system evaluated in parallel parts writes its own entries).
  void store_by_swap(const OdeSystem& system, double t, const Vector& y, Vector& f);
  /// f(t, y) from memory when possible, otherwise evaluated and stored.
  void evaluate(const OdeSystem& system, double t, const Vector& y, Vector& f);
  void clear() { system_ = nullptr; }

 private:
  /// Whether the stored f belongs to exactly (system, t, y).
  bool holds(const OdeSystem& system, double t, const Vector& y) const;
  void remember_point(const OdeSystem& system, double t, const Vector& y);

  const OdeSystem* system_ = nullptr;
  double t_ = 0.0;
  Vector y_, f_;
};

}  // namespace jellysim::ode
