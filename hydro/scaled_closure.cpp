#include "hydro/scaled_closure.hpp"

#include <cmath>
#include <limits>

#include "fields/constants.hpp"
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
// the general criteria of hydro/closure.hpp: the clustering mode grows while
// p_n (kappa kx^2 + Lambda_T') < p_T (Lambda_n + mu kx^2), i.e. while
// (kappa - mu p_T/p_n) kx^2 < p_T Lambda_n/p_n - Lambda_T', the shear mode while
// eta_xy kx^2 < eps, with k = kx / (2 pi). (mu = 0 leaves the conduction kappa as it is, bit for
// bit: kappa - 0 = kappa.) Should mu p_T/p_n reach kappa, every short wave clusters: no cutoff.
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
  const double pressure_balanced_conductivity =
      h.conductivity - h.mu * h.pressure_temperature / h.pressure_density;
  const double clustering =
      (h.pressure_temperature * h.cooling_density / h.pressure_density - h.cooling_temperature) /
      pressure_balanced_conductivity;
  h.clustering_cutoff_mode = !(pressure_balanced_conductivity > 0.0)
                                 ? std::numeric_limits<double>::infinity()
                             : clustering > 0 ? std::sqrt(clustering) / kTwoPi
                                              : 0.0;
  h.shear_cutoff_mode = std::sqrt(h.epsilon / h.shear_viscosity) / kTwoPi;
  return h;
}

}  // namespace granvv::hydro
