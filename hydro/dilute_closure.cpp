#include "hydro/dilute_closure.hpp"

#include "fields/constants.hpp"
#include "hydro/haff.hpp"
#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

DiluteClosure::DiluteClosure(const Physics& physics, CoolingRate cooling, double area_fraction)
    : physics_(physics),
      area_fraction_(area_fraction),
      loss_factor_(inelastic_loss_factor(cooling, physics.q)),
      cooling_coefficient_(8.0 * physics.q / physics.K * loss_factor_) {}

void DiluteClosure::cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                      CellCoefficients& out) const {
  fill_coefficients(n, T, out);
}

GRANVV_WIDE_LOOPS
void DiluteClosure::fill_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                      CellCoefficients& out) const {
  const size_t cells = n.size();
  out.resize(cells);
#pragma GCC ivdep  // element i reads only element i
  for (size_t i = 0; i < cells; ++i) {
    const double ni = n[i], Ti = T[i];  // loaded once: the outputs might alias the inputs
    out.pressure[i] = pressure(ni, Ti);
    out.adiabatic_modulus[i] = adiabatic_modulus(ni, Ti);
    const double sqrt_T = std::sqrt(Ti);
    const double eta = viscosity_of_root(sqrt_T);
    out.viscosity[i] = eta;
    out.shear_viscosity[i] = eta;
    out.conductivity[i] = conductivity_of_root(sqrt_T);
    out.mu[i] = 0.0;  // no heat flux down the density gradient (docs/physics.md §9)
  }
}

void DiluteClosure::sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                                std::vector<double>& c) const {
  fill_sound_speed(n, T, c);
}

GRANVV_WIDE_LOOPS
void DiluteClosure::fill_sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                                     std::vector<double>& c) const {
  c.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) c[i] = sound_speed(T[i]);
}

void DiluteClosure::cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                                 std::vector<double>& rate) const {
  rate.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) rate[i] = cooling_rate(n[i], T[i]);
}

void DiluteClosure::cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
                         std::vector<double>& cooled) const {
  fill_cooled(n, T, dt, cooled);
}

GRANVV_WIDE_LOOPS
void DiluteClosure::fill_cooled(const std::vector<double>& n, const std::vector<double>& T,
                                double dt, std::vector<double>& cooled) const {
  cooled.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    cooled[i] = cool_exactly(T[i], n[i], cooling_coefficient_, dt);
  }
}

HcsLinearisation DiluteClosure::hcs_linearisation() const {
  HcsLinearisation h;
  // Haff: dT/dt = -(8q/K) g T^{3/2}, t0 = K/(4q g) (paper, after Eq. 2, g = 1); +inf for q = 0.
  // g = 1 exactly for the paper's cooling, so these are its K/(4q) and 4q/K bit for bit.
  const double q_eff = physics_.q * loss_factor_;
  h.haff_time = physics_.K / (4.0 * q_eff);
  h.epsilon = 4.0 * physics_.q / physics_.K * loss_factor_;
  h.pressure_density = 1.0;      // dp/dn = T
  h.pressure_temperature = 1.0;  // dp/dT = n
  h.compression_heating = pressure(1.0, 1.0);
  h.viscosity = viscosity(1.0);
  h.shear_viscosity = viscosity(1.0);
  h.conductivity = conductivity(1.0);
  h.mu = 0.0;                           // so the cutoffs below need no mu term
  h.cooling_density = 2.0 * h.epsilon;  // Lambda/n = 8q/K
  h.cooling_temperature = h.epsilon;    // (3/2 - 1) Lambda = 4q/K
  // det A = -kx^2 (K kx^2 - eps) and eps - K kx^2/4: pi k K < sqrt(q g), < 2 sqrt(q g).
  h.clustering_cutoff_mode = std::sqrt(q_eff) / (kPi * physics_.K);
  h.shear_cutoff_mode = 2.0 * std::sqrt(q_eff) / (kPi * physics_.K);
  return h;
}

ValidityScales DiluteClosure::validity_scales() const {
  return {physics_.K, area_fraction_, false, kDiluteAreaFractionLimit};
}

}  // namespace granvv::hydro
