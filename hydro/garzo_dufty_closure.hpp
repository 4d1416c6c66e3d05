#pragma once
// The inelastic kinetic-theory closure of the scaled 2D granular hydrodynamics,
// hydro.closure = "garzo_dufty" (docs/physics.md §9): the Navier-Stokes transport of smooth
// inelastic hard disks of restitution r = 1 - 2q in the first Sonine approximation
// (hydro/garzo_dufty_coefficients.hpp), with Enskog's factors of the local area fraction
// phi = phi0 n (hydro/enskog_factors.hpp) for a dense gas:
//   p = n T F_p,  eta = (K/4) T^{1/2} eta* F_eta,  eta_xy = (K/4) T^{1/2} eta* F_eta_xy,
//   kappa = K T^{1/2} kappa* F_kappa,  mu = K T^{3/2} mu* F_kappa / n,
//   Lambda = (8q/K) g (1 + 3 a2/16) n T^{3/2} F_zeta,
// with g the inelastic-loss factor of physics.cooling (hydro/cooling_rate.hpp; "exact" makes
// Lambda Garzo & Dufty's zeta T). (K/4) T^{1/2}, K T^{1/2} and K T^{3/2}/n are the elastic
// dilute eta0, kappa0 and T kappa0/n in the paper's scaling. phi0 = 0 (physics.area_fraction not
// given) is the dilute gas, where every Enskog factor is 1. The dense form is a product: the
// r-dependence of the dilute gas times the elastic Enskog factors, so it leaves out the
// r-dependence of the collisional transfer (Garzo & Dufty 1999, Sec. IV), a correction of
// order (1 - r) phi. At r = 1 it is the Enskog closure, at phi0 = 0 and r = 1 the dilute one.
// It is the Enskog closure with the multipliers eta*, kappa*, mu*, 1 + 3 a2/16
// (InelasticTransport, hydro/enskog_closure.hpp), allowing phi0 = 0.
#include <memory>
#include <optional>
#include <string>

#include "hydro/enskog_closure.hpp"
#include "hydro/garzo_dufty_coefficients.hpp"

namespace granvv::hydro {

class GarzoDuftyClosure final : public EnskogClosure {
 public:
  // area_fraction phi0 in [0, kFreezingAreaFraction), 0: dilute; and r with kappa* > mu*
  // (r > 0.345). Else std::invalid_argument.
  GarzoDuftyClosure(const Physics& physics, double area_fraction, CoolingRate cooling);
  static std::unique_ptr<Closure> make(const ClosureParameters& params);
  static std::optional<ClosureParameterProblem> parameter_problem(const ClosureParameters& params);

  const garzo_dufty::DiluteCoefficients& reduced() const { return reduced_; }
  std::string name() const override { return "garzo_dufty"; }

 private:
  GarzoDuftyClosure(const Physics& physics, double area_fraction, CoolingRate cooling,
                    const garzo_dufty::DiluteCoefficients& reduced);

  garzo_dufty::DiluteCoefficients reduced_;
};

}  // namespace granvv::hydro
