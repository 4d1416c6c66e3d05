#pragma once
// The dilute closure of the scaled 2D granular hydrodynamics, paper Eqs. (1)-(2) (Efrati,
// Livne & Meerson, PRL 94, 088001 (2005); docs/physics.md §1, §9):
//   p = n T,  eta = eta_xy = (K/4) T^{1/2},  kappa = K T^{1/2},  mu = 0,
//   Lambda = (8q/K) g n T^{3/2},
// with g = 1 (the paper) or 1 - q (physics.cooling = "exact", hydro/cooling_rate.hpp).
// The 2D ideal gas has adiabatic index 2 (T ~ n on an adiabat), so B = 2p and c^2 = 2T. The
// xy shear viscosity of the dilute gas equals the longitudinal one (no bulk viscosity), so it
// also drives the transverse velocity v_y(x) (docs/physics.md §6).
#include <cmath>

#include "hydro/closure.hpp"
#include "hydro/physics.hpp"

namespace granvv::hydro {

// The local area fraction up to which the dilute closure is taken to hold (its validity
// monitor's threshold, docs/physics.md §9): at phi = 0.1 Henderson's chi is 1.18, so the
// dilute gas misses 18 % of the collisions and, at r = 0.9, 22 % of the pressure.
inline constexpr double kDiluteAreaFractionLimit = 0.1;

class DiluteClosure final : public Closure {
 public:
  // area_fraction: phi0 of the gas when it is known (0: not), read only by the validity
  // monitors; the dilute equations do not depend on it.
  explicit DiluteClosure(const Physics& physics, CoolingRate cooling = CoolingRate::small_q,
                         double area_fraction = 0.0);

  // The formulas, one per quantity, for one cell.
  static double pressure(double n, double T) { return n * T; }
  static double adiabatic_modulus(double n, double T) { return 2.0 * pressure(n, T); }
  static double sound_speed(double T) { return std::sqrt(2.0 * T); }
  double viscosity(double T) const { return viscosity_of_root(std::sqrt(T)); }
  double conductivity(double T) const { return conductivity_of_root(std::sqrt(T)); }
  // c = (8q/K) g of the sink Lambda = c n T^{3/2}.
  double cooling_coefficient() const { return cooling_coefficient_; }
  double cooling_rate(double n, double T) const {
    return cooling_coefficient_ * n * T * std::sqrt(T);
  }

  const Physics& physics() const { return physics_; }

  std::string name() const override { return "dilute"; }
  void cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                         CellCoefficients& out) const override;
  void sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                   std::vector<double>& c) const override;
  void cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                    std::vector<double>& rate) const override;
  void cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
            std::vector<double>& cooled) const override;
  HcsLinearisation hcs_linearisation() const override;
  ValidityScales validity_scales() const override;

 private:
  // The loops of cell_coefficients, sound_speed and cool, compiled for wide vectors where the
  // CPU has them (hydro/wide_loops.hpp: a virtual function cannot be multiversioned).
  void fill_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                         CellCoefficients& out) const;
  void fill_sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                        std::vector<double>& c) const;
  void fill_cooled(const std::vector<double>& n, const std::vector<double>& T, double dt,
                   std::vector<double>& cooled) const;
  // eta and kappa from T^{1/2}, which they share.
  double viscosity_of_root(double sqrt_T) const { return 0.25 * physics_.K * sqrt_T; }
  double conductivity_of_root(double sqrt_T) const { return physics_.K * sqrt_T; }

  Physics physics_;
  double area_fraction_;  // phi0, 0 = not known
  double loss_factor_;    // g
  double cooling_coefficient_;
};

}  // namespace granvv::hydro
