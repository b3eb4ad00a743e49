#include "jellysim/ode/derivative_cache.hpp"

namespace jellysim::ode {

bool DerivativeCache::holds(const OdeSystem& system, double t, const Vector& y) const {
  return system_ == &system && t_ == t && y_.size() == y.size() && (y_.array() == y.array()).all();
}

void DerivativeCache::remember_point(const OdeSystem& system, double t, const Vector& y) {
  system_ = &system;
  t_ = t;
  y_ = y;
}

bool DerivativeCache::lookup(const OdeSystem& system, double t, const Vector& y, Vector& f) const {
  const bool hit = holds(system, t, y);
  if (hit) f = f_;
  return hit;
}

void DerivativeCache::store(const OdeSystem& system, double t, const Vector& y, const Vector& f) {
  remember_point(system, t, y);
  f_ = f;
}

bool DerivativeCache::take(const OdeSystem& system, double t, const Vector& y, Vector& f) {
  const bool hit = holds(system, t, y);
  if (hit) {
    f.swap(f_);
    clear();
  }
  return hit;
}

void DerivativeCache::store_by_swap(const OdeSystem& system, double t, const Vector& y, Vector& f) {
  remember_point(system, t, y);
  f_.swap(f);
}

void DerivativeCache::evaluate(const OdeSystem& system, double t, const Vector& y, Vector& f) {
  if (lookup(system, t, y, f)) return;
  f.resize(system.dimension());
  system.derivative(t, y, f);
  store(system, t, y, f);
}

}  // namespace jellysim::ode
