#pragma once
// Symmetric positive-definite periodic tridiagonal systems in O(N) with LAPACK: the reference
// (test oracle) for the batched solver the Lagrangian scheme uses (hydro/batched_tridiagonal). The
// periodic corner couples unknowns n-1 and 0; it is removed by a rank-one (Sherman-Morrison)
// correction, A = T - w w^T / gamma, where T is the plain tridiagonal matrix A + w w^T / gamma with
// w = (gamma, 0, ..., 0, -c), c the corner entry and gamma = A(0,0). T is then SPD whenever A is,
// so LAPACK's dpttrf/dpttrs (L D L^T of an SPD tridiagonal matrix) factor and solve it; A is SPD
// exactly when T is and gamma - w^T T^-1 w > 0.
#include <vector>

namespace granvv::hydro {

class PeriodicTridiagonalSolver {
 public:
  explicit PeriodicTridiagonalSolver(int n);

  // Factorise A with A(i,i) = diag[i] and A(i,i+1) = A(i+1,i) = upper[i] (i+1 taken mod n).
  // Returns false if the matrix is not positive definite.
  bool factorize(const std::vector<double>& diag, const std::vector<double>& upper);
  // Solve with the last factorisation; rhs and solution may alias.
  void solve(const std::vector<double>& rhs, std::vector<double>& solution);
  int size() const { return n_; }

 private:
  int n_;
  std::vector<double> d_, e_;                              // L D L^T factors of T (dpttrf)
  std::vector<double> z_;                                  // T^-1 w
  double gamma_ = 0.0, corner_ = 0.0, denominator_ = 0.0;  // gamma, c, gamma - w^T T^-1 w
};

}  // namespace granvv::hydro
