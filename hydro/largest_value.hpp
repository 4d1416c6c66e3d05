#pragma once
// The largest element of an array, for the per-step scans of the hydro (validity monitors, the
// heating limit): four interleaved running maxima, independent chains the compiler can pack
// into vector maxima, where one running maximum is a chain of dependent comparisons.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace granvv::hydro {

// The largest of values and of `floor`; NaN elements are skipped.
inline double largest_value(const std::vector<double>& values, double floor = 0.0) {
  std::array<double, 4> partial{floor, floor, floor, floor};
  const std::size_t n = values.size();
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    for (std::size_t k = 0; k < 4; ++k) {
      partial[k] = values[i + k] > partial[k] ? values[i + k] : partial[k];
    }
  }
  for (; i < n; ++i) partial[0] = values[i] > partial[0] ? values[i] : partial[0];
  return std::max(std::max(partial[0], partial[1]), std::max(partial[2], partial[3]));
}

}  // namespace granvv::hydro
