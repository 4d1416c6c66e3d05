#include "atlas/detectable_error.hpp"

#include <cmath>
#include <stdexcept>

namespace granvv::atlas {

std::vector<double> default_injected_errors() {
  std::vector<double> eps;
  for (int k = 0; k <= 16; ++k) eps.push_back(0.01 * std::pow(2.0, 0.5 * k));
  return eps;
}

bool catches_injected_error(const JudgedHydro& perturbed, const JudgedHydro& unperturbed) {
  if (!perturbed.finished || !perturbed.model_disagreement) return false;
  if (!unperturbed.finished) return false;  // no baseline to part from
  if (unperturbed.agreed_throughout) return true;
  if (!unperturbed.agreed_until) return false;  // it never agreed: nothing earlier to part at
  return !perturbed.agreed_until || *perturbed.agreed_until < *unperturbed.agreed_until;
}

bool off_by_transport_fit(double fitted, double error, double hydro_factor, double sigmas) {
  if (!std::isfinite(fitted) || !std::isfinite(error) || !(error > 0.0)) return false;
  return std::abs(hydro_factor - fitted) > sigmas * error;
}

bool catches_by_transport_fit(double fitted, double error, double injected_factor, double sigmas) {
  return off_by_transport_fit(fitted, error, injected_factor, sigmas) &&
         !off_by_transport_fit(fitted, error, 1.0, sigmas);
}

std::optional<double> smallest_detectable(const std::vector<double>& epsilons,
                                          const std::vector<bool>& caught,
                                          const std::vector<bool>& finished) {
  if (caught.size() != epsilons.size() || finished.size() != epsilons.size()) {
    throw std::invalid_argument("smallest_detectable: grid, caught and finished differ in size");
  }
  for (std::size_t i = 1; i < epsilons.size(); ++i) {
    if (!(epsilons[i] > epsilons[i - 1])) {
      throw std::invalid_argument("smallest_detectable: the grid must increase");
    }
  }
  std::optional<double> from;
  for (std::size_t i = epsilons.size(); i-- > 0;) {
    if (!finished[i]) continue;
    if (!caught[i]) break;
    from = epsilons[i];
  }
  return from;
}

}  // namespace granvv::atlas
