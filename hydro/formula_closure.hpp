#pragma once
// A closure from the user's formulas, hydro.closure = "formula" (docs/physics.md §9): the
// pressure p, the longitudinal and shear viscosities eta and eta_xy, the conductivity kappa,
// the inelastic heat-flux coefficient mu and the cooling sink Lambda as muparser expressions of
// n and T in the scaled variables of docs/physics.md §1 (hydro/formula.hpp), with the case's K,
// q, r = 1 - 2q, phi0 (physics.area_fraction, 0 = not given) and the user's hydro.constants.
// As in every closure, physics.cooling = "exact" multiplies Lambda by 1 - q
// (hydro/cooling_rate.hpp). The defaults are the dilute closure's formulas
// (hydro/dilute_closure.hpp), so that "formula" alone is the dilute closure.
//
// What the formulas do not give is taken numerically:
//  - the adiabatic modulus B = n dp/dn + p (dp/dT) / n (along the adiabat dT = p dn / n^2) and
//    c^2 = B / n, and the derivatives of p and Lambda in the linear theory, by fourth-order
//    central differences with a step 1e-3 of the variable (hydro/central_difference.hpp):
//    truncation ~1e-12 f^(5) n^5 / f and round-off ~3e-13, relative;
//  - the cooling step, dT/dt = -Lambda at fixed n, integrated in u = T^{-1/2} (du/dt =
//    Lambda T^{-3/2} / 2, constant for the hard-disk scaling Lambda ~ T^{3/2}, where one
//    step is exact) by the Dormand-Prince 5(4) pair with its local error held below 1e-13 u.
//
// Before a run the formulas are checked on a log grid of (n, T) (kCheckedTemperatures, n from
// kLowestCheckedDensity to hydro.density_limit): every value finite, and p, B, eta, eta_xy,
// kappa and Lambda > 0; mu may have either sign. A run stops (RunStatus::closure_limit) where
// a cell's density passes hydro.density_limit.
#include <optional>
#include <string>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/formula.hpp"

namespace granvv::hydro {

// The grid of the check: n in [kLowestCheckedDensity, hydro.density_limit] and T in
// [kCheckedTemperatures[0], [1]], kCheckPointsPerDecade points per decade of each.
inline constexpr double kLowestCheckedDensity = 1e-6;
inline constexpr double kCheckedTemperatures[2] = {1e-12, 1e4};
inline constexpr int kCheckPointsPerDecade = 4;

class FormulaClosure final : public Closure {
 public:
  // The closure's own case keys hydro.<name> (closure.hpp, ClosureKey), with their defaults.
  static std::vector<ParameterSpec> keys();
  static std::unique_ptr<Closure> make(const ClosureParameters& params);
  // The first formula that does not compile or fails the check, its key and why.
  static std::optional<ClosureParameterProblem> parameter_problem(const ClosureParameters& params);

  // Compiles the formulas of params (its texts and tables, the defaults where absent); throws
  // std::invalid_argument with parameter_problem's reason where they fail the check.
  explicit FormulaClosure(const ClosureParameters& params);

  std::string name() const override { return "formula"; }
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

  // One cell.
  double adiabatic_modulus(double n, double T) const;
  double cooling_rate(double n, double T) const;
  // T after cooling for dt at fixed n (NaN where Lambda is not finite on the way).
  double cooled(double n, double T, double dt) const;

 private:
  Physics physics_;
  double area_fraction_;  // phi0, 0 = not known
  double density_limit_;  // hydro.density_limit
  double loss_factor_;    // g of physics.cooling
  // p, eta, eta_xy, kappa, mu, Lambda without g (the order of keys()).
  std::vector<Formula> formulas_;
};

}  // namespace granvv::hydro
