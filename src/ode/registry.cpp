// The by-name registry of integrators (one table, so names and factories cannot drift apart).
#include <array>

#include "jellysim/ode/backward_euler.hpp"
#include "jellysim/ode/explicit_runge_kutta.hpp"
#include "jellysim/ode/integrator.hpp"
#include "jellysim/ode/leapfrog.hpp"

namespace jellysim::ode {

namespace {

struct Entry {
  std::string_view name;
  std::unique_ptr<Integrator> (*make)();
};

template <ButcherTableau (*tableau)()>
std::unique_ptr<Integrator> make_runge_kutta() {
  return std::make_unique<ExplicitRungeKutta>(tableau());
}

template <typename T>
std::unique_ptr<Integrator> make_default() {
  return std::make_unique<T>();
}

constexpr std::array<Entry, 7> kRegistry{{
    {"forward-euler", make_runge_kutta<forward_euler_tableau>},
    {"predictor-corrector", make_runge_kutta<predictor_corrector_tableau>},
    {"leapfrog", make_default<Leapfrog>},
    {"rk2", make_runge_kutta<rk2_tableau>},
    {"rk4", make_runge_kutta<rk4_tableau>},
    {"dopri5", make_runge_kutta<dopri5_tableau>},
    {"backward-euler", make_default<BackwardEuler>},
}};

std::string joined_names() {
  std::string out;
  for (const Entry& entry : kRegistry) out += (out.empty() ? "" : ", ") + std::string(entry.name);
  return out;
}

}  // namespace

const std::vector<std::string>& integrator_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Entry& entry : kRegistry) out.emplace_back(entry.name);
    return out;
  }();
  return names;
}

std::unique_ptr<Integrator> make_integrator(std::string_view name) {
  for (const Entry& entry : kRegistry) {
    if (entry.name == name) return entry.make();
  }
  throw std::invalid_argument("unknown integrator '" + std::string(name) + "'; allowed: " + joined_names());
}

}  // namespace jellysim::ode
