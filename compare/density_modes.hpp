#pragma once
// Fourier modes of fields on the particles' bins, and the perturbation of the homogeneous
// cooling state they carry, in the variables of hydro/linear_stability.hpp (paper Eqs. 1-2
// linearised: nu = n/n0 - 1, w = v / T_H^{1/2}, theta = T/T_H - 1), so that linear theory can
// evolve a measured state mode by mode.
#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace granvv::compare {

// c_k = sum_b f_b dx exp(-2 pi i k x_b) for values f_b at the centres x_b of equal bins of
// [-1/2, 1/2): the amplitude of mode k (f = sum_k c_k exp(2 pi i k x)).
std::complex<double> bin_fourier_coefficient(const std::vector<double>& values, int k);

// (nu_k, w_k, theta_k) of binned n, v_x, T (any units: n is taken relative to its mean, T to
// its mass-weighted mean T_H, v in units of T_H^{1/2}). Throws std::invalid_argument on sizes
// that differ or an empty or non-positive field.
Eigen::Vector3cd hcs_perturbation(const std::vector<double>& n, const std::vector<double>& v,
                                  const std::vector<double>& T, int k);

}  // namespace granvv::compare
