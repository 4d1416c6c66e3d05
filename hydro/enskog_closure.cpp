#include "hydro/enskog_closure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hydro/enskog_factors.hpp"
#include "hydro/haff.hpp"
#include "hydro/number_text.hpp"
#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

EnskogClosure::EnskogClosure(const Physics& physics, double area_fraction, CoolingRate cooling,
                             const InelasticTransport& transport)
    : physics_(physics),
      area_fraction_(area_fraction),
      restitution_(1.0 - 2.0 * physics.q),
      transport_(transport),
      cooling_coefficient_(8.0 * physics.q / physics.K * inelastic_loss_factor(cooling, physics.q) *
                           transport.cooling) {}

EnskogClosure::EnskogClosure(const Physics& physics, double area_fraction, CoolingRate cooling)
    : EnskogClosure(physics, area_fraction, cooling, InelasticTransport{}) {
  if (const auto problem =
          parameter_problem({physics, {{kAreaFractionParameter, area_fraction}}})) {
    throw std::invalid_argument("enskog closure: area fraction " + number_text(area_fraction) +
                                ": " + problem->reason);
  }
}

double EnskogClosure::area_fraction_in(const ClosureParameters& params) {
  const auto it = params.extra.find(kAreaFractionParameter);
  return it == params.extra.end() ? 0.0 : it->second;
}

std::unique_ptr<Closure> EnskogClosure::make(const ClosureParameters& params) {
  return std::make_unique<EnskogClosure>(params.physics, area_fraction_in(params), params.cooling);
}

std::optional<ClosureParameterProblem> EnskogClosure::parameter_problem(
    const ClosureParameters& params) {
  const double phi0 = area_fraction_in(params);
  if (phi0 > 0.0 && phi0 < enskog::kFreezingAreaFraction) return std::nullopt;
  return ClosureParameterProblem{kAreaFractionParameter,
                                 "the enskog closure needs the mean area fraction phi0 in (0, " +
                                     number_text(enskog::kFreezingAreaFraction) +
                                     "), below the freezing of hard disks"};
}

void EnskogClosure::cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                      CellCoefficients& out) const {
  fill_coefficients(n, T, out);
}

GRANVV_WIDE_LOOPS
void EnskogClosure::fill_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                      CellCoefficients& out) const {
  const size_t cells = n.size();
  out.resize(cells);
  const double eta0 = 0.25 * physics_.K * transport_.viscosity;
  const double kappa0 = physics_.K * transport_.conductivity;
  const double mu0 = physics_.K * transport_.mu;
  const double r = restitution_;
#pragma GCC ivdep  // element i reads only element i
  for (size_t i = 0; i < cells; ++i) {
    const double ni = n[i], Ti = T[i];  // loaded once: the outputs might alias the inputs
    const double phi = area_fraction_ * ni;
    const double nT = ni * Ti;
    out.pressure[i] = nT * enskog::pressure_factor(phi, r);
    out.adiabatic_modulus[i] = nT * enskog::sound_speed_factor(phi, r);
    const double sqrt_T = std::sqrt(Ti);
    out.viscosity[i] = eta0 * sqrt_T * enskog::viscosity_factor(phi);
    out.shear_viscosity[i] = eta0 * sqrt_T * enskog::shear_viscosity_factor(phi);
    const double f_kappa = enskog::conductivity_factor(phi);
    out.conductivity[i] = kappa0 * sqrt_T * f_kappa;
    out.mu[i] = mu0 * Ti * sqrt_T * f_kappa / ni;  // T kappa0 mu* F_kappa / n (0: mu* = 0)
  }
}

void EnskogClosure::sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                                std::vector<double>& c) const {
  fill_sound_speed(n, T, c);
}

GRANVV_WIDE_LOOPS
void EnskogClosure::fill_sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                                     std::vector<double>& c) const {
  c.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    c[i] = std::sqrt(T[i] * enskog::sound_speed_factor(area_fraction_ * n[i], restitution_));
  }
}

void EnskogClosure::cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                                 std::vector<double>& rate) const {
  rate.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    const double effective_n = n[i] * enskog::cooling_factor(area_fraction_ * n[i]);
    rate[i] = cooling_coefficient_ * effective_n * T[i] * std::sqrt(T[i]);
  }
}

void EnskogClosure::cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
                         std::vector<double>& cooled) const {
  fill_cooled(n, T, dt, cooled);
}

GRANVV_WIDE_LOOPS
void EnskogClosure::fill_cooled(const std::vector<double>& n, const std::vector<double>& T,
                                double dt, std::vector<double>& cooled) const {
  // At fixed n the sink is c (n chi) T^{3/2}: Haff's exact solution with n chi for n.
  cooled.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    const double effective_n = n[i] * enskog::cooling_factor(area_fraction_ * n[i]);
    cooled[i] = cool_exactly(T[i], effective_n, cooling_coefficient_, dt);
  }
}

HcsLinearisation EnskogClosure::hcs_linearisation() const {
  // At n = T = 1: phi = phi0. Derivatives in n go through phi = phi0 n (d/dn = phi0 d/dphi).
  const double phi = area_fraction_, r = restitution_;
  const double chi = enskog::cooling_factor(phi);
  const double f_p = enskog::pressure_factor(phi, r);
  HcsLinearisation h;
  const double rate = cooling_coefficient_ * chi;  // Lambda(1, 1)
  h.haff_time = 2.0 / rate;                        // +inf for q = 0
  h.epsilon = 0.5 * rate;
  h.pressure_density = f_p + phi * enskog::pressure_factor_derivative(phi, r);
  h.pressure_temperature = f_p;
  h.compression_heating = f_p;
  h.viscosity = 0.25 * physics_.K * transport_.viscosity * enskog::viscosity_factor(phi);
  h.shear_viscosity =
      0.25 * physics_.K * transport_.viscosity * enskog::shear_viscosity_factor(phi);
  const double f_kappa = enskog::conductivity_factor(phi);
  h.conductivity = physics_.K * transport_.conductivity * f_kappa;
  h.mu = physics_.K * transport_.mu * f_kappa;
  // Lambda = c n chi(phi0 n) T^{3/2}: dLambda/dn = c (chi + phi chi').
  h.cooling_density = cooling_coefficient_ * (chi + phi * enskog::cooling_factor_derivative(phi));
  h.cooling_temperature = h.epsilon;  // (3/2 - 1) Lambda
  // The clustering mode grows while (p_n kappa - p_T mu) kx^2 < p_T Lambda_n - p_n Lambda_T'
  // (hydro/closure.hpp); were p_n kappa <= p_T mu, every short wave would (no closure here lets
  // it: hydro/garzo_dufty_closure.cpp). mu = 0 subtracts an exact 0.
  const double damping = h.pressure_density * h.conductivity - h.pressure_temperature * h.mu;
  const double clustering_kx2 =
      (h.pressure_temperature * h.cooling_density - h.pressure_density * h.cooling_temperature) /
      damping;
  const double shear_kx2 = h.epsilon / h.shear_viscosity;
  h.clustering_cutoff_mode = damping > 0.0 ? std::sqrt(std::max(clustering_kx2, 0.0)) / (2.0 * kPi)
                                           : std::numeric_limits<double>::infinity();
  h.shear_cutoff_mode = std::sqrt(std::max(shear_kx2, 0.0)) / (2.0 * kPi);
  return h;
}

ValidityScales EnskogClosure::validity_scales() const {
  // Collisions carry chi wherever phi0 is known (always for the Enskog closure itself).
  return {physics_.K, area_fraction_, area_fraction_ > 0.0, enskog::kFreezingAreaFraction};
}

std::string EnskogClosure::validity_problem(const std::vector<double>& n) const {
  return freezing_problem(area_fraction_, n, name());
}

std::string freezing_problem(double area_fraction, const std::vector<double>& n,
                             const std::string& closure) {
  size_t densest = 0;
  for (size_t i = 1; i < n.size(); ++i) {
    if (n[i] > n[densest]) densest = i;
  }
  if (n.empty() || area_fraction * n[densest] < enskog::kFreezingAreaFraction) return {};
  return "the area fraction phi0 n = " + number_text(area_fraction * n[densest]) + " in cell " +
         std::to_string(densest) + " reached the freezing fraction " +
         number_text(enskog::kFreezingAreaFraction) + " of hard disks, past which the " + closure +
         " closure does not apply";
}

}  // namespace granvv::hydro
