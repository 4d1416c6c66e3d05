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

// Multipliers an inelastic kinetic theory puts on the elastic dilute transport and cooling of
// the Enskog closure's terms (hydro/garzo_dufty_closure.hpp): eta = (K/4) T^{1/2} eta* F_eta,
// kappa = K T^{1/2} kappa* F_kappa, mu = K T^{3/2} mu* F_kappa / n, and the sink times `cooling`.
// The Enskog closure's own are the identity, with mu* = 0 (multiplying by 1 and adding 0 are
// exact, so it computes what it did without them, bit for bit).
struct InelasticTransport {
  double viscosity = 1.0;     // eta*
  double conductivity = 1.0;  // kappa*
  double mu = 0.0;            // mu*
  double cooling = 1.0;       // multiplies Lambda
};

class EnskogClosure : public Closure {
 public:
  // The parameter it reads from ClosureParameters::extra.
  static constexpr const char* kAreaFractionParameter = "area_fraction";
  // physics.area_fraction as the parameters carry it (0 when not given: the dilute gas).
  static double area_fraction_in(const ClosureParameters& params);

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

 protected:
  // With the multipliers of an inelastic theory and phi0 unchecked (0: the dilute gas), for a
  // closure built on this one that checks its own parameters.
  EnskogClosure(const Physics& physics, double area_fraction, CoolingRate cooling,
                const InelasticTransport& transport);

 private:
  // The loops of cell_coefficients, sound_speed and cool, compiled for wide vectors where the
  // CPU has them (hydro/wide_loops.hpp: a virtual function cannot be multiversioned).
  void fill_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                         CellCoefficients& out) const;
  void fill_sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                        std::vector<double>& c) const;
  void fill_cooled(const std::vector<double>& n, const std::vector<double>& T, double dt,
                   std::vector<double>& cooled) const;

  Physics physics_;
  double area_fraction_;  // phi0: phi = phi0 n
  double restitution_;    // r = 1 - 2q
  InelasticTransport transport_;
  double cooling_coefficient_;  // (8q/K) g times transport_.cooling
};

// Why a closure of dense hard disks no longer describes cells of densities n (empty while it
// does): the densest cell's area fraction phi0 n reached the freezing fraction. `closure` names
// the closure in the reason.
std::string freezing_problem(double area_fraction, const std::vector<double>& n,
                             const std::string& closure);

}  // namespace granvv::hydro
