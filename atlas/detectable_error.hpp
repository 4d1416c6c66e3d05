#pragma once
// Comparison power (docs/atlas.md): how small a model error the side-by-side comparison with a
// particle ensemble can catch. The hydro is run with one transport coefficient multiplied by a
// known factor (hydro/transport_factors.hpp) and judged against the same particles as the
// unperturbed hydro; the comparison catches the injected error when it flags a `model`
// disagreement that the unperturbed hydro does not have (an earlier parting, or a parting where
// the unperturbed hydro agreed throughout).
#include <optional>
#include <vector>

namespace granvv::atlas {

// The injected relative errors eps tried by default: a log grid 0.01 * 2^(k/2), k = 0 .. 16
// (0.01 to 2.56), so that a detectable eps is known to within a factor sqrt(2).
std::vector<double> default_injected_errors();

// What the side-by-side judgement of one hydro says (compare/side_by_side.hpp): whether it
// flagged a model disagreement, and until when its fields agreed (nullopt: not at the first
// compared time).
struct JudgedHydro {
  bool finished = false;  // the hydro run reached every compared time without failing
  bool model_disagreement = false;
  bool agreed_throughout = false;
  std::optional<double> agreed_until;
};

// Whether `perturbed` catches its injected error against `unperturbed` (above). Nothing is
// caught when either run did not finish.
bool catches_injected_error(const JudgedHydro& perturbed, const JudgedHydro& unperturbed);

// The transport fit's judgement (docs/atlas.md, "Comparison power"): the particles' fitted
// factor F on the closure's coefficient, with its jackknife standard error, against a hydro whose
// coefficient is `hydro_factor` times the closure's. The hydro is off when it lies more than
// `sigmas` standard errors from F. Nothing is off for a non-finite F or an error that is not
// positive (no fit).
bool off_by_transport_fit(double fitted, double error, double hydro_factor, double sigmas);
// An injected error is caught when its hydro (at `injected_factor`) is off while the unperturbed
// closure (factor 1) is not; when the closure itself is off, nothing is caught.
bool catches_by_transport_fit(double fitted, double error, double injected_factor, double sigmas);

// The smallest eps of an increasing grid from which every larger eps that finished is caught;
// nullopt when the largest finished eps is not caught (nothing up to it is detectable).
// `caught` is over the grid; `finished` says which runs count. Throws std::invalid_argument on
// sizes that differ or a grid that does not increase.
std::optional<double> smallest_detectable(const std::vector<double>& epsilons,
                                          const std::vector<bool>& caught,
                                          const std::vector<bool>& finished);

}  // namespace granvv::atlas
