#pragma once
// Symmetric periodic tridiagonal systems (the implicit viscous and conductive parts of
// the Lagrangian scheme) solved by Eigen's sparse LDL^T. The sparsity pattern is fixed,
// so it is analysed once and only the numeric factorisation is repeated.
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
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
  Eigen::SparseMatrix<double> matrix_;  // upper triangle only
  std::vector<double*> diag_entry_, upper_entry_;
  // Natural order: a periodic tridiagonal matrix fills in only its last column, so a
  // fill-reducing permutation buys nothing; with the upper triangle stored column-major,
  // Eigen factorises the matrix in place instead of copying it at every factorisation.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>
      ldlt_;
  Eigen::VectorXd rhs_, solution_;
};

}  // namespace granvv::hydro
