#include "hydro/periodic_tridiagonal.hpp"

#include <lapacke.h>

#include <cmath>
#include <stdexcept>

namespace granvv::hydro {

PeriodicTridiagonalSolver::PeriodicTridiagonalSolver(int n) : n_(n), d_(n), e_(n - 1), z_(n) {
  if (n < 3) throw std::invalid_argument("periodic tridiagonal system needs at least 3 unknowns");
}

bool PeriodicTridiagonalSolver::factorize(const std::vector<double>& diag,
                                          const std::vector<double>& upper) {
  const int n = n_;
  gamma_ = diag[0];
  corner_ = upper[n - 1];
  if (!(gamma_ > 0.0)) return false;
  for (int i = 0; i < n; ++i) d_[i] = diag[i];
  for (int i = 0; i + 1 < n; ++i) e_[i] = upper[i];
  d_[0] += gamma_;
  d_[n - 1] += corner_ * corner_ / gamma_;
  if (LAPACKE_dpttrf_work(n, d_.data(), e_.data()) != 0) return false;
  z_.assign(n, 0.0);
  z_[0] = gamma_;
  z_[n - 1] = -corner_;
  LAPACKE_dpttrs_work(LAPACK_COL_MAJOR, n, 1, d_.data(), e_.data(), z_.data(), n);
  denominator_ = gamma_ - (gamma_ * z_[0] - corner_ * z_[n - 1]);
  return denominator_ > 0.0 && std::isfinite(denominator_);
}

void PeriodicTridiagonalSolver::solve(const std::vector<double>& rhs,
                                      std::vector<double>& solution) {
  const int n = n_;
  if (&solution != &rhs) solution = rhs;
  LAPACKE_dpttrs_work(LAPACK_COL_MAJOR, n, 1, d_.data(), e_.data(), solution.data(), n);
  // x = y + z (w^T y) / (gamma - w^T z), y = T^-1 b.
  const double scale = (gamma_ * solution[0] - corner_ * solution[n - 1]) / denominator_;
  for (int i = 0; i < n; ++i) solution[i] += scale * z_[i];
}

}  // namespace granvv::hydro
