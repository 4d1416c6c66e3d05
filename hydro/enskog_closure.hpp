#pragma once
// The Enskog dense-gas closure of the scaled 2D granular hydrodynamics (docs/physics.md §9):
// each term of the dilute closure (hydro/dilute_closure.hpp) times an Enskog factor of the
// local area fraction phi = phi0 n (hydro/enskog_factors.hpp), with r = 1 - 2q:
//   p = n T F_p,  eta = (K/4) T^{1/2} F_eta,  eta_xy = (K/4) T^{1/2} F_eta_xy,
//   kappa = K T^{1/2} F_kappa,  mu = 0,  Lambda = (8q/K) g n T^{3/2} F_zeta,
// with g the inelastic-loss factor of physics.cooling (hydro/cooling_rate.hpp). The adiabatic
// modulus is B = n c^2 = n T (F_p + F_p^2 + phi dF_p/dphi). At phi0 -> 0 every factor is 1 and
// the closure is the dilute one. Past the freezing fraction the closure reports itself invalid.
#include <string>
#include <vector>

#include "hydro/closure.hpp"

namespace granvv::hydro {

class EnskogClosure final : public Closure {
 public:
  // The parameter it reads from ClosureParameters::extra.
  static constexpr const char* kAreaFractionParameter = "area_fraction";

  // area_fraction phi0 in (0, kFreezingAreaFraction) (else std::invalid_argument).
  EnskogClosure(const Physics& physics, double area_fraction, CoolingRate cooling);
  static std::unique_ptr<Closure> make(const ClosureParameters& params);
  static std::optional<ClosureParameterProblem> parameter_problem(const ClosureParameters& params);

  double area_fraction() const { return area_fraction_; }

  std::string name() const override { return "enskog"; }
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
  std::string validity_problem(const std::vector<double>& n) const override;

 private:
  Physics physics_;
  double area_fraction_;        // phi0: phi = phi0 n
  double restitution_;          // r = 1 - 2q
  double cooling_coefficient_;  // (8q/K) g
};

}  // namespace granvv::hydro
