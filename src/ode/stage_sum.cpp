#include "jellysim/ode/stage_sum.hpp"

#include <array>
#include <utility>

namespace jellysim::ode {

namespace {

constexpr std::size_t kTermsPerPass = 8;

struct Terms {
  std::array<double, kTermsPerPass> c{};
  std::array<const Vector*, kTermsPerPass> k{};
  std::size_t count = 0;
};

/// out = base + c_0 k_0 + c_1 k_1 + ... on the segment: a left fold, so each entry is summed in term
/// order, as the one-term-at-a-time passes would.
template <class Base, std::size_t... I>
void assign_sum(Eigen::Ref<Eigen::VectorXd> out, const Base& base, const Terms& t, Eigen::Index start,
                Eigen::Index length, std::index_sequence<I...>) {
  out = (base + ... + (t.c[I] * t.k[I]->segment(start, length)));
}

template <class Base>
void assign(Eigen::Ref<Eigen::VectorXd> out, const Base& base, const Terms& t, Eigen::Index start, Eigen::Index length) {
  switch (t.count) {
    case 0: out = base; break;
    case 1: assign_sum(out, base, t, start, length, std::make_index_sequence<1>()); break;
    case 2: assign_sum(out, base, t, start, length, std::make_index_sequence<2>()); break;
    case 3: assign_sum(out, base, t, start, length, std::make_index_sequence<3>()); break;
    case 4: assign_sum(out, base, t, start, length, std::make_index_sequence<4>()); break;
    case 5: assign_sum(out, base, t, start, length, std::make_index_sequence<5>()); break;
    case 6: assign_sum(out, base, t, start, length, std::make_index_sequence<6>()); break;
    case 7: assign_sum(out, base, t, start, length, std::make_index_sequence<7>()); break;
    default: assign_sum(out, base, t, start, length, std::make_index_sequence<kTermsPerPass>()); break;
  }
}

/// The passes of form_stage_segment; without y (nullptr) the first pass starts from zero.
void form_segment(const Vector* y, double h, std::span<const double> weights, std::span<const Vector> k, Vector& out,
                  Eigen::Index start, Eigen::Index length) {
  auto segment = out.segment(start, length);
  bool first_pass = true;
  std::size_t j = 0;
  // Up to kTermsPerPass terms per pass; a second pass (more terms than any tableau here has) adds
  // to the first one's result, which keeps the order of the additions.
  do {
    Terms t;
    for (; j < weights.size() && t.count < kTermsPerPass; ++j) {
      if (weights[j] == 0.0) continue;
      t.c[t.count] = h * weights[j];
      t.k[t.count] = &k[j];
      ++t.count;
    }
    if (first_pass && y != nullptr) {
      assign(segment, y->segment(start, length), t, start, length);
    } else if (first_pass) {
      assign(segment, Vector::Zero(length), t, start, length);
    } else {
      const Vector partial = segment;  // the fold reads its base while writing: keep it apart
      assign(segment, partial, t, start, length);
    }
    first_pass = false;
  } while (j < weights.size());
}

}  // namespace

void form_stage_segment(const Vector& y, double h, std::span<const double> weights, std::span<const Vector> k,
                        Vector& out, Eigen::Index start, Eigen::Index length) {
  form_segment(&y, h, weights, k, out, start, length);
}

void form_weighted_sum(double h, std::span<const double> weights, std::span<const Vector> k, Vector& out) {
  const Eigen::Index n = k.empty() ? 0 : k[0].size();
  out.resize(n);
  form_segment(nullptr, h, weights, k, out, 0, n);
}

void form_stage_state(const Vector& y, double h, std::span<const double> weights, std::span<const Vector> k,
                      Vector& out) {
  out.resize(y.size());
  form_stage_segment(y, h, weights, k, out, 0, y.size());
}

}  // namespace jellysim::ode

namespace jellysim::ode {

void OdeSystem::compute_stage_derivative(double t, const Vector& y, double h, std::span<const double> weights,
                                         std::span<const Vector> k, Vector& y_stage, Vector& dydt) const {
  form_stage_state(y, h, weights, k, y_stage);
  compute_derivative(t, y_stage, dydt);
}

}  // namespace jellysim::ode
