#include "hydro/periodic_tridiagonal.hpp"

#include <stdexcept>

namespace granvv::hydro {

PeriodicTridiagonalSolver::PeriodicTridiagonalSolver(int n)
    : n_(n), matrix_(n, n), diag_entry_(n), upper_entry_(n), rhs_(n), solution_(n) {
  if (n < 3) throw std::invalid_argument("periodic tridiagonal system needs at least 3 unknowns");
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 1.0);
    const int j = (i + 1) % n;
    entries.emplace_back(std::min(i, j), std::max(i, j), 0.0);
  }
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    diag_entry_[i] = &matrix_.coeffRef(i, i);
    upper_entry_[i] = &matrix_.coeffRef(std::min(i, j), std::max(i, j));
  }
  ldlt_.analyzePattern(matrix_);
}

bool PeriodicTridiagonalSolver::factorize(const std::vector<double>& diag,
                                          const std::vector<double>& upper) {
  for (int i = 0; i < n_; ++i) {
    *diag_entry_[i] = diag[i];
    *upper_entry_[i] = upper[i];
  }
  ldlt_.factorize(matrix_);
  return ldlt_.info() == Eigen::Success;
}

void PeriodicTridiagonalSolver::solve(const std::vector<double>& rhs,
                                      std::vector<double>& solution) {
  for (int i = 0; i < n_; ++i) rhs_[i] = rhs[i];
  solution_ = ldlt_.solve(rhs_);
  solution.resize(n_);
  for (int i = 0; i < n_; ++i) solution[i] = solution_[i];
}

}  // namespace granvv::hydro
