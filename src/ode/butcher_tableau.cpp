#include "jellysim/ode/butcher_tableau.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace jellysim::ode {

ButcherTableau forward_euler_tableau() {
  return {.name = "forward-euler", .c = {0.0}, .a = {{}}, .b = {1.0}, .b_hat = {}, .order = 1};
}

ButcherTableau predictor_corrector_tableau() {
  // Predictor (eq. 2.26) is the second stage's argument; the step uses only the corrector slope.
  return {.name = "predictor-corrector", .c = {0.0, 1.0}, .a = {{}, {1.0}}, .b = {0.0, 1.0}, .b_hat = {}, .order = 1};
}

ButcherTableau rk2_tableau() {
  return {.name = "rk2",
          .c = {0.0, 1.0},
          .a = {{}, {1.0}},
          .b = {0.5, 0.5},
          .b_hat = {1.0, 0.0},
          .order = 2,
          .embedded_order = 1};
}

ButcherTableau rk4_tableau() {
  return {.name = "rk4",
          .c = {0.0, 0.5, 0.5, 1.0},
          .a = {{}, {0.5}, {0.0, 0.5}, {0.0, 0.0, 1.0}},
          .b = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0},
          .b_hat = {},
          .order = 4};
}

ButcherTableau dopri5_tableau() {
  // J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6 (1980) 19-26; Hairer, Nørsett & Wanner,
  // Solving ODEs I, Table II.5.2. The last row of A equals b (FSAL).
  const std::vector<double> b{35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0};
  return {.name = "dopri5",
          .c = {0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0},
          .a = {{},
                {1.0 / 5.0},
                {3.0 / 40.0, 9.0 / 40.0},
                {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
                {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
                {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
                {b.begin(), b.end() - 1}},
          .b = b,
          .b_hat = {5179.0 / 57600.0, 0.0, 7571.0 / 16695.0, 393.0 / 640.0, -92097.0 / 339200.0, 187.0 / 2100.0,
                    1.0 / 40.0},
          .order = 5,
          .embedded_order = 4,
          .fsal = true};
}

namespace {

void require(bool condition, const ButcherTableau& tableau, const char* what) {
  if (!condition) throw std::invalid_argument("Butcher tableau '" + tableau.name + "': " + what);
}

bool sums_to(const std::vector<double>& values, double target) {
  return std::abs(std::accumulate(values.begin(), values.end(), 0.0) - target) < 1e-14;
}

void validate_shape(const ButcherTableau& tableau) {
  const std::size_t s = tableau.stages();
  require(s > 0, tableau, "no stages");
  require(tableau.c.size() == s && tableau.a.size() == s, tableau, "c, A and b differ in length");
  require(tableau.b_hat.empty() || tableau.b_hat.size() == s, tableau, "b_hat has the wrong length");
  require(tableau.b_hat.empty() == (tableau.embedded_order == 0), tableau, "embedded order without b_hat");
  for (std::size_t i = 0; i < s; ++i) require(tableau.a[i].size() == i, tableau, "A is not strictly lower");
}

void validate_consistency(const ButcherTableau& tableau) {
  for (std::size_t i = 0; i < tableau.stages(); ++i)
    require(sums_to(tableau.a[i], tableau.c[i]), tableau, "c_i != sum_j a_ij");
  require(sums_to(tableau.b, 1.0), tableau, "weights b do not sum to 1");
  require(tableau.b_hat.empty() || sums_to(tableau.b_hat, 1.0), tableau, "weights b_hat do not sum to 1");
}

void validate_fsal(const ButcherTableau& tableau) {
  if (!tableau.fsal) return;
  const std::size_t last = tableau.stages() - 1;
  require(last > 0 && tableau.c[last] == 1.0 && tableau.b[last] == 0.0, tableau, "FSAL needs c_s = 1, b_s = 0");
  const std::vector<double> b_head(tableau.b.begin(), tableau.b.end() - 1);
  require(tableau.a[last] == b_head, tableau, "FSAL needs the last row of A to equal b");
}

}  // namespace

void validate(const ButcherTableau& tableau) {
  validate_shape(tableau);
  validate_consistency(tableau);
  validate_fsal(tableau);
}

}  // namespace jellysim::ode
