#pragma once
// The median of a sample, as the timing code (PathChooser, benchmarks) compares them.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace jellysim {

/// The median of `values` (non-empty; reordered): the upper of the middle two for an even count.
inline double median(std::vector<double>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace jellysim
