#include "hydro/garzo_dufty_closure.hpp"

#include <stdexcept>

#include "hydro/enskog_factors.hpp"
#include "hydro/number_text.hpp"

namespace granvv::hydro {

GarzoDuftyClosure::GarzoDuftyClosure(const Physics& physics, double area_fraction,
                                     CoolingRate cooling)
    : GarzoDuftyClosure(physics, area_fraction, cooling,
                        garzo_dufty::dilute_coefficients(1.0 - 2.0 * physics.q)) {
  if (const auto problem =
          parameter_problem({physics, {{EnskogClosure::kAreaFractionParameter, area_fraction}}})) {
    throw std::invalid_argument("garzo_dufty closure: " + problem->parameter + ": " +
                                problem->reason);
  }
}

GarzoDuftyClosure::GarzoDuftyClosure(const Physics& physics, double area_fraction,
                                     CoolingRate cooling,
                                     const garzo_dufty::DiluteCoefficients& reduced)
    : EnskogClosure(
          physics, area_fraction, cooling,
          {reduced.viscosity, reduced.conductivity, reduced.mu, 1.0 + 3.0 * reduced.a2 / 16.0}),
      reduced_(reduced) {}

std::unique_ptr<Closure> GarzoDuftyClosure::make(const ClosureParameters& params) {
  return std::make_unique<GarzoDuftyClosure>(
      params.physics, EnskogClosure::area_fraction_in(params), params.cooling);
}

std::optional<ClosureParameterProblem> GarzoDuftyClosure::parameter_problem(
    const ClosureParameters& params) {
  // A mode at pressure balance is conducted by kappa - mu p_T/p_n >= kappa - mu n/T (p_T <= p_n):
  // the first Sonine kappa* - mu* falls through 0 near r = 0.345, below which the closure would
  // sharpen such a mode instead of smoothing it.
  const double r = 1.0 - 2.0 * params.physics.q;
  const auto reduced = garzo_dufty::dilute_coefficients(r);
  if (!(reduced.conductivity - reduced.mu > 0.0)) {
    return ClosureParameterProblem{
        "q", "the garzo_dufty closure's conduction at pressure balance kappa* - mu* = " +
                 number_text(reduced.conductivity - reduced.mu) + " at r = " + number_text(r) +
                 " is not positive (first Sonine approximation; it is for r > 0.345)"};
  }
  const double phi0 = EnskogClosure::area_fraction_in(params);
  if (phi0 >= 0.0 && phi0 < enskog::kFreezingAreaFraction) return std::nullopt;
  return ClosureParameterProblem{
      EnskogClosure::kAreaFractionParameter,
      "the garzo_dufty closure needs the mean area fraction phi0 in [0, " +
          number_text(enskog::kFreezingAreaFraction) +
          "), below the freezing of hard disks (0: the dilute gas)"};
}

}  // namespace granvv::hydro
