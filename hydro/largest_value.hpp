#pragma once
// The largest element of an array and where it first occurs, for the per-step scans of the hydro
// (validity monitors, the heating limit). Eight running maxima side by side, one per lane of a
// GCC vector (one AVX-512 register, or several narrower ones), each with the index where its lane
// first reached its maximum: independent chains where one running maximum is a chain of
// dependent comparisons, and a single pass where finding the index afterwards is a second scan.
// Maxima are exact, so the order of the comparisons changes no result.
#include <cstddef>
#include <cstring>
#include <vector>

namespace granvv::hydro {

struct LargestAt {
  double value = 0.0;  // the largest of the elements and of the floor
  int at = 0;          // the first element holding it (0 where none exceeds the floor)
};

// NaN elements are skipped (a NaN is never greater).
inline LargestAt largest_with_index(const std::vector<double>& values, double floor = 0.0) {
  constexpr int kLanes = 8;
  using Lanes = double __attribute__((vector_size(8 * kLanes)));
  using LaneIndexes = long long __attribute__((vector_size(8 * kLanes)));
  const int n = static_cast<int>(values.size());
  Lanes best;
  LaneIndexes at{}, index;
  for (int k = 0; k < kLanes; ++k) best[k] = floor, index[k] = k;
  int i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    Lanes x;
    std::memcpy(&x, values.data() + i, sizeof x);
    const LaneIndexes greater = x > best;  // per lane: strictly greater keeps the first
    best = greater ? x : best;
    at = greater ? index : at;
    index += kLanes;
  }
  LargestAt out{floor, 0};
  for (int k = 0; k < kLanes; ++k) {  // across lanes: the largest, and of equals the first index
    if (best[k] > out.value || (best[k] == out.value && best[k] > floor && at[k] < out.at)) {
      out = {best[k], static_cast<int>(at[k])};
    }
  }
  for (; i < n; ++i) {  // the rest lie after every element the lanes saw
    if (values[std::size_t(i)] > out.value) out = {values[std::size_t(i)], i};
  }
  return out;
}

// The largest of values and of `floor`; NaN elements are skipped.
inline double largest_value(const std::vector<double>& values, double floor = 0.0) {
  return largest_with_index(values, floor).value;
}

}  // namespace granvv::hydro
