#include "compare/jackknife.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace granvv::compare {
namespace {

void require_rectangular(const std::vector<std::vector<double>>& members, std::size_t minimum) {
  if (members.size() < minimum) {
    throw std::invalid_argument("jackknife: needs at least " + std::to_string(minimum) +
                                " members, got " + std::to_string(members.size()));
  }
  for (const auto& row : members) {
    if (row.size() != members.front().size()) {
      throw std::invalid_argument("jackknife: members of different lengths");
    }
  }
}

}  // namespace

std::vector<double> member_mean(const std::vector<std::vector<double>>& members) {
  require_rectangular(members, 1);
  std::vector<double> sum(members.front().size(), 0.0);
  for (const auto& row : members) {
    for (std::size_t s = 0; s < row.size(); ++s) sum[s] += row[s];
  }
  for (double& v : sum) v /= double(members.size());
  return sum;
}

std::vector<std::vector<double>> leave_one_out_means(
    const std::vector<std::vector<double>>& members) {
  require_rectangular(members, 2);
  const double m = double(members.size());
  std::vector<double> sum = member_mean(members);
  for (double& v : sum) v *= m;
  std::vector<std::vector<double>> samples;
  for (const auto& row : members) {
    std::vector<double> without(row.size());
    for (std::size_t s = 0; s < row.size(); ++s) without[s] = (sum[s] - row[s]) / (m - 1.0);
    samples.push_back(std::move(without));
  }
  return samples;
}

double jackknife_error(const std::vector<double>& estimates) {
  const double m = double(estimates.size());
  if (estimates.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double mean = 0.0;
  for (double f : estimates) mean += f / m;
  double squares = 0.0;
  for (double f : estimates) squares += (f - mean) * (f - mean);
  return std::sqrt((m - 1.0) / m * squares);
}

double jackknife_correlation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("jackknife: estimates of different counts");
  double mean_a = 0.0, mean_b = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) mean_a += a[i], mean_b += b[i];
  mean_a /= double(a.size()), mean_b /= double(b.size());
  double covariance = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) covariance += (a[i] - mean_a) * (b[i] - mean_b);
  const double m = double(a.size());
  covariance *= (m - 1.0) / m;
  return covariance / (jackknife_error(a) * jackknife_error(b));
}

std::vector<double> jackknife_errors(const std::vector<std::vector<double>>& samples) {
  std::vector<double> errors;
  if (samples.empty()) return errors;
  for (std::size_t s = 0; s < samples.front().size(); ++s) {
    std::vector<double> column;
    for (const auto& row : samples) column.push_back(row[s]);
    errors.push_back(jackknife_error(column));
  }
  return errors;
}

}  // namespace granvv::compare
