#pragma once
// The delete-one jackknife over the members of an ensemble (Efron & Tibshirani, "An
// Introduction to the Bootstrap", ch. 11): sample i is the mean of every member but i, and the
// standard error of an estimate f made from the ensemble mean is
//   se_J(f) = sqrt( (M - 1)/M * sum_i (f_(i) - f_(.))^2 ),   f_(.) = mean of the f_(i),
// with f_(i) the same estimate made from sample i. For f the mean itself se_J is exactly the
// standard error s / sqrt(M). A member is a row of values (one per snapshot, say); values of one
// member are correlated with each other however they are, and an f made from several of them
// (a fitted coefficient) carries those correlations into its error.
#include <vector>

namespace granvv::compare {

// The column means over the members (rows, all of one length). Throws std::invalid_argument
// without members or for ragged rows.
std::vector<double> member_mean(const std::vector<std::vector<double>>& members);

// samples[i]: the column means without member i. Throws std::invalid_argument with fewer than
// two members or for ragged rows.
std::vector<std::vector<double>> leave_one_out_means(
    const std::vector<std::vector<double>>& members);

// se_J of one estimate from its leave-one-out values f_(i) (NaN for fewer than two).
double jackknife_error(const std::vector<double>& leave_one_out_estimates);

// The correlation of two estimates' jackknife errors from their leave-one-out values (of equal
// length, at least two): cov_J / (se_J(a) se_J(b)), cov_J = (M - 1)/M sum_i (a_(i) - a_(.))
// (b_(i) - b_(.)).
double jackknife_correlation(const std::vector<double>& a, const std::vector<double>& b);

// se_J of each column of the leave-one-out samples (the error of each column mean).
std::vector<double> jackknife_errors(const std::vector<std::vector<double>>& samples);

}  // namespace granvv::compare
