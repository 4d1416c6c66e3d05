#pragma once
// The standard error of an ensemble-mean field, bin by bin (docs/physics.md §7).
//
// One snapshot's error model (md_bridge/coarse_grainer.hpp: sqrt(T/N) for a velocity component,
// T/sqrt(N - 1) for T, Poisson n/sqrt(N) for n) gives the shape of the error over the bins. With
// k >= 2 members the ensemble calibrates its level: the model variance is scaled by the pooled
// ratio R = mean over bins of (observed ensemble variance / model variance), where the observed
// variance of one member is k SE_b^2 (SE_b the standard error of the mean over the k members). R
// has bins (k - 1) degrees of freedom, so the error of each bin does not rest on its own k - 1
// alone (with k = 3 a t-distribution puts only 90 % of pure noise within 3 standard errors),
// while correlations the model ignores (density fluctuations with S(0) != 1, hydrodynamic
// modes) still enter through the ensemble. The error of the mean over k_b members is then
//   error_b = model_b sqrt(R / k_b).
// A single member (or no bin with a usable model and scatter) keeps the model, R = 1.
#include <string>
#include <vector>

#include "compare/ensemble_statistics.hpp"

namespace granvv::compare {

struct EnsembleMeanError {
  std::vector<double> error;    // per bin, in the units of the model
  double variance_ratio = 1.0;  // R; 1 when not calibrated
  int members = 1;              // the most members any bin had
  bool calibrated = false;      // R measured from at least one bin with k >= 2
};

// model_one_member: one member's snapshot error per bin (NaN or <= 0 where it has none);
// statistics: the ensemble of that field (ensemble_statistics), bin by bin, as long as the
// model.
EnsembleMeanError ensemble_mean_error(const std::vector<double>& model_one_member,
                                      const EnsembleStatistics& statistics);

// Where the error came from, for the outputs: "ensemble of k (model error x sqrt(R))" or
// "single-snapshot model".
std::string error_source_label(const EnsembleMeanError& error);

}  // namespace granvv::compare
