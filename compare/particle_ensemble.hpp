#pragma once
// The reduction of an ensemble of particle runs (independent seeds of one scene) to what the
// scene reports: the temperature's ensemble mean and standard error, the homogeneous window and
// the Haff fit over it (compare/haff_window.hpp, compare/haff_fit.hpp), and the box's pressure
// (P_xx + P_yy)/2 and compressibility factor Z = P/(n T) averaged over the samples and the
// members with their standard errors (compare/sample_average.hpp). Plain data in, so that any
// engine's runs reduce the same way.
#include <vector>

#include "compare/ensemble_statistics.hpp"
#include "compare/haff_fit.hpp"
#include "compare/haff_window.hpp"
#include "compare/sample_average.hpp"

namespace granvv::compare {

// One member's sampled series (md_bridge/md_run.hpp, MdSeries), all at the same sample times.
struct MemberSamples {
  std::vector<double> t, T, mode_energy_fraction;
  // The box's pressure tensor diagonal, the single-sample standard error of (P_xx + P_yy)/2 and
  // Z; NaN where the engine gave no contact virial.
  std::vector<double> pressure_xx, pressure_yy, pressure_stderr, compressibility;
};

struct ParticleEnsemble {
  EnsembleStatistics T, mode_energy_fraction;  // at member 0's sample times
  HomogeneousWindow homogeneous;
  HaffFit haff;  // t0, t0_error and T0 NaN when there is no fit (too few samples, no cooling)
  SampleAverage pressure, compressibility;
};

// The sample's pressure p = (P_xx + P_yy)/2 carries the error sigma_p; Z = p/(n T) carries the
// same relative error, sigma_Z = sigma_p Z / p (n and T of the sample taken as exact).
SampleAverage ensemble_pressure(const std::vector<MemberSamples>& members);
SampleAverage ensemble_compressibility(const std::vector<MemberSamples>& members);

// members non-empty. The Haff fit runs from t = 0 to the end of the homogeneous window, which
// closes when the mean mode-energy fraction first exceeds mode_energy_threshold (t_end: never).
ParticleEnsemble reduce_particle_ensemble(const std::vector<MemberSamples>& members,
                                          double mode_energy_threshold, double t_end);

}  // namespace granvv::compare
