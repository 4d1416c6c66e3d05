#pragma once
// Periodic interpolation of tabulated values y_i at strictly increasing x_i within one period
// (x_last < x_0 + 1): piecewise linear, or monotone cubic (Hermite with the Fritsch-Butland
// harmonic-mean slopes, which keep the interpolant within the neighbouring values, so n > 0
// and T > 0 stay positive, and make no new extrema). The interval from x_last to x_0 + 1 closes
// the period.
#include <functional>
#include <string>
#include <vector>

namespace granvv::hydro {

enum class Interpolation { linear, monotone_cubic };
// "linear", "cubic"
const std::vector<std::string>& interpolation_names();
Interpolation interpolation_from_name(const std::string& name);  // std::invalid_argument

// Requires x.size() == y.size() >= 2 and the order above (std::invalid_argument otherwise).
std::function<double(double)> periodic_interpolant(const std::vector<double>& x,
                                                   const std::vector<double>& y,
                                                   Interpolation interpolation);

}  // namespace granvv::hydro
