#pragma once
// Homogeneous cooling measured over a range of restitution coefficients r, against kinetic
// theory. For smooth inelastic disks the cooling rate of the temperature at T0 is
// zeta = 2 / t0 = sqrt(pi) (1 - r^2) chi(phi) n sigma sqrt(T0/m) (docs/physics.md §4), so the
// measured zeta should scale as (1 - r^2)^1. The paper's hydro keeps the small-q form 8q/K, i.e. 1
// - r^2 ~ 4q = 2 (1 - r), which overestimates the rate by the factor 2 / (1 + r); at finite density
// it also lacks chi(phi) unless that is put in.
#include <optional>
#include <vector>

#include "compare/power_law_fit.hpp"

namespace granvv::compare {

struct CoolingPoint {
  double restitution = 0.0;                 // r as run
  double t0 = 0.0, t0_error = 0.0;          // measured Haff time and its standard error
  double t0_enskog = 0.0, t0_dilute = 0.0;  // kinetic theory with chi(phi) and with chi = 1
  double t0_paper = 0.0;                    // the paper's hydro, K / 4q, in the same units
};

// The standard errors beyond which a sweep's measured cooling is said to depart from a theory
// (the Enskog rate, the paper's small-q rate, kinetic theory's power 1 of 1 - r^2).
inline constexpr double kCoolingSweepSigmas = 3.0;

struct CoolingSweep {
  double sigmas = 0.0;  // as given
  // Per point: the measured t0 against kinetic theory with chi(phi): t0 / t0_enskog - 1, the
  // same difference in standard errors of t0, and whether that exceeds `sigmas`.
  std::vector<double> enskog_deviation, enskog_deviation_sigmas;
  std::vector<bool> enskog_beyond_sigmas;
  // Per point: cooling rates zeta = 2 / t0 (error 2 dt0 / t0^2).
  std::vector<double> zeta, zeta_error, zeta_enskog, zeta_dilute, zeta_paper, zeta_paper_enskog;
  // The paper's small-q rate with chi(phi) against the measured one: relative deviation and
  // the same in standard errors of the measurement.
  std::vector<double> paper_deviation, paper_deviation_sigmas;
  std::vector<bool> paper_beyond_sigmas;  // |paper_deviation_sigmas| > sigmas
  // zeta = C (1 - r^2)^p fitted over the points with r >= power_r_min (nullopt: < 2 points).
  std::optional<PowerLawFit> power;
  double power_r_min = 0.0;
  // Kinetic theory's power 1 (docs/physics.md §4) against the fitted p: (p - 1) / dp, and
  // whether |(p - 1) / dp| <= sigmas (nullopt without a fit, or with a non-finite deviation).
  std::optional<double> power_deviation_from_one_sigmas;
  std::optional<bool> power_consistent_with_one;
  // The largest r at which the small-q rate (with chi) misses the measured rate by more than
  // `sigmas` standard errors (nullopt: it never does).
  std::optional<double> paper_departs_at;
};

// Points in any order; r must lie in (0, 1). Throws std::invalid_argument on a point without a
// positive, finite t0 and error.
CoolingSweep analyse_cooling_sweep(const std::vector<CoolingPoint>& points, double power_r_min,
                                   double sigmas);

}  // namespace granvv::compare
