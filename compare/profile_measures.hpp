#pragma once
// Simple measures of a profile on the periodic bins of [-1/2, 1/2) (scaled units): its
// mass-weighted mean, where it peaks, and its slope there. The comparison scales the velocity
// and temperature differences by the mass-weighted mean temperature, and follows the density
// peak and the velocity gradient at it (the steepening flow of paper Fig. 3).
#include <cstddef>
#include <vector>

namespace granvv::compare {

// sum n g / sum n over the bins where both n and g are finite (NaN if there are none).
double mass_weighted_mean(const std::vector<double>& n, const std::vector<double>& g);

// The bin of the largest value (the first of equal ones); 0 for an empty profile.
std::size_t peak_bin(const std::vector<double>& values);

// The centred difference (v_{b+1} - v_{b-1}) / (2 dx) at bin b, periodic, with dx = 1 / bins.
double periodic_centred_slope(const std::vector<double>& values, std::size_t b);

}  // namespace granvv::compare
