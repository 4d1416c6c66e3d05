#include "compare/density_modes.hpp"

#include <cmath>
#include <stdexcept>

#include "fields/constants.hpp"
namespace granvv::compare {

std::complex<double> bin_fourier_coefficient(const std::vector<double>& values, int k) {
  std::complex<double> c = 0.0;
  const double dx = 1.0 / values.size();
  for (std::size_t b = 0; b < values.size(); ++b) {
    const double x = -0.5 + (b + 0.5) * dx;
    c += values[b] * dx * std::exp(std::complex<double>(0.0, -2.0 * kPi * k * x));
  }
  return c;
}

Eigen::Vector3cd hcs_perturbation(const std::vector<double>& n, const std::vector<double>& v,
                                  const std::vector<double>& T, int k) {
  if (n.empty() || n.size() != v.size() || v.size() != T.size()) {
    throw std::invalid_argument("hcs_perturbation: n, v and T need the same, non-zero length");
  }
  double mass = 0.0, heat = 0.0;
  for (std::size_t b = 0; b < n.size(); ++b) mass += n[b], heat += n[b] * T[b];
  if (!(mass > 0.0) || !(heat > 0.0)) {
    throw std::invalid_argument("hcs_perturbation: density and temperature must be positive");
  }
  const double n_mean = mass / n.size(), T_mean = heat / mass;
  std::vector<double> nu, w, theta;
  for (std::size_t b = 0; b < n.size(); ++b) {
    nu.push_back(n[b] / n_mean - 1.0);
    w.push_back(v[b] / std::sqrt(T_mean));
    theta.push_back(T[b] / T_mean - 1.0);
  }
  return {bin_fourier_coefficient(nu, k), bin_fourier_coefficient(w, k),
          bin_fourier_coefficient(theta, k)};
}

}  // namespace granvv::compare
