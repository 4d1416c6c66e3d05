#include "hydro/scaled_closure.hpp"

#include "hydro/hcs_cutoffs.hpp"

namespace granvv::hydro {
namespace {

void scale(std::vector<double>& column, double factor) {
  for (double& value : column) value *= factor;
}

}  // namespace

ScaledClosure::ScaledClosure(std::unique_ptr<Closure> closure, const TransportFactors& factors)
    : closure_(std::move(closure)), factors_(factors) {}

void ScaledClosure::cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                      CellCoefficients& out) const {
  closure_->cell_coefficients(n, T, out);
  scale(out.viscosity, factors_.viscosity);
  scale(out.shear_viscosity, factors_.viscosity);
  scale(out.conductivity, factors_.conductivity);
  scale(out.mu, factors_.mu);
}

void ScaledClosure::sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                                std::vector<double>& c) const {
  closure_->sound_speed(n, T, c);
}

void ScaledClosure::cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                                 std::vector<double>& rate) const {
  closure_->cooling_rate(n, T, rate);
  scale(rate, factors_.cooling);
}

// dT/dt = -f Lambda(n, T) at fixed n is the wrapped closure's cooling run for f dt: the sink
// does not depend on time.
void ScaledClosure::cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
                         std::vector<double>& cooled) const {
  closure_->cool(n, T, factors_.cooling * dt, cooled);
}

// The wrapped closure's linearisation with the scaled coefficients; the two cutoffs follow from
// the general criteria (hydro/hcs_cutoffs.hpp). (mu = 0 leaves the conduction kappa as it is,
// bit for bit: kappa - 0 = kappa.)
HcsLinearisation ScaledClosure::hcs_linearisation() const {
  HcsLinearisation h = closure_->hcs_linearisation();
  h.viscosity *= factors_.viscosity;
  h.shear_viscosity *= factors_.viscosity;
  h.conductivity *= factors_.conductivity;
  h.mu *= factors_.mu;
  h.haff_time /= factors_.cooling;
  h.epsilon *= factors_.cooling;
  h.cooling_density *= factors_.cooling;
  h.cooling_temperature *= factors_.cooling;
  set_cutoff_modes(h);
  return h;
}

}  // namespace granvv::hydro
