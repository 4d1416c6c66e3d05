#include "compare/inertia_measures.hpp"

#include <cmath>
#include <complex>

#include "compare/density_modes.hpp"

namespace granvv::compare {

double sine_mode_amplitude(const std::vector<double>& values, int k) {
  return -2.0 * bin_fourier_coefficient(values, k).imag();
}

double cosine_mode_amplitude(const std::vector<double>& values, int k) {
  return 2.0 * bin_fourier_coefficient(values, k).real();
}

double central_window_mass(const std::vector<double>& n, double half_width) {
  const std::size_t bins = n.size();
  double mass = 0.0;
  for (std::size_t b = 0; b < bins; ++b) {
    const double x = -0.5 + (b + 0.5) / bins;
    if (std::abs(x) < half_width) mass += n[b];
  }
  return mass / bins;
}

double central_density(const std::vector<double>& n) {
  const std::size_t bins = n.size();
  if (bins % 2 == 1) return n[bins / 2];
  return 0.5 * (n[bins / 2 - 1] + n[bins / 2]);
}

}  // namespace granvv::compare
