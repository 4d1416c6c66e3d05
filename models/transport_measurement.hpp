#pragma once
// A transport coefficient measured from a scene's particle ensemble (docs/physics.md §14): the
// k = 1 amplitude of the scene's field in every member (compare/mode_amplitudes.hpp), the hydro
// run with the coefficient's factors at a grid of values, F fitted to the particles with its
// jackknife error and chi^2 (compare/transport_factor_fit.hpp), and every value relative to
// the elastic dilute coefficient of hard disks (compare/transport_coefficients.hpp).
#include <string>
#include <utility>
#include <vector>

#include "compare/transport_coefficients.hpp"
#include "compare/transport_factor_fit.hpp"
#include "models/compare_scene.hpp"

namespace granvv::app {

// The factors of compare.transport_factors = [].
inline const std::vector<double> kDefaultTransportFactors = {0.5, 0.75, 1.0, 1.25, 1.5};

struct TransportMeasurement {
  std::string coefficient, field, phase;  // compare.transport, _field, _phase
  std::string closure;                    // hydro.closure: F is a factor on its coefficient
  std::vector<double> t;                  // the snapshots' scaled times (t[0]: the start)
  compare::FactorGrid grid;               // the hydro's amplitudes at the factors
  compare::FactorFit fit;
  // F times the closure's value and its error, relative to the elastic dilute value.
  double measured = 0.0, error = 0.0;
  // Each closure of compare.closures with its value relative to the elastic dilute one, in
  // that order (the first is hydro.closure's).
  std::vector<std::pair<std::string, double>> closures;
};

// The hydro's amplitude of `field`'s `phase` part at each of the times, from its snapshots at
// those times; `kept` gets the indices of the times it has a snapshot at.
std::vector<double> hydro_mode_amplitudes(const fields::FieldSeries& hydro,
                                          const std::string& field, compare::ModePhase phase,
                                          const std::vector<double>& times,
                                          std::vector<std::size_t>& kept);

// The snapshots of `kept` that are also in `found`, in kept's order.
std::vector<std::size_t> snapshots_in_both(const std::vector<std::size_t>& kept,
                                           const std::vector<std::size_t>& found);
// Throws std::runtime_error, naming compare.transport_start, unless `kept` begins at `start` and
// holds at least three snapshots.
void require_fit_snapshots(const std::vector<std::size_t>& kept, std::size_t start);
// row[s] for s in kept.
std::vector<double> select_snapshots(const std::vector<double>& row,
                                     const std::vector<std::size_t>& kept);

// The closure `closure`'s value of `coefficient` relative to the elastic dilute one, at the
// homogeneous state (n = T = 1) of `hydro` with no injected factors.
double closure_coefficient_value(const compare::TransportCoefficient& coefficient,
                                 const HydroScene& hydro, const std::string& closure);

// hydro: the comparison's hydro (aligned with the particles, from their t = 0 fields where the
// case says so); closures: compare.closures. Runs the hydro once per factor of the grid, on the
// particles' bins. Throws std::runtime_error when a hydro run of the grid fails or the snapshots
// are too few to fit.
TransportMeasurement measure_transport(const CompareScene::Transport& transport,
                                       const std::vector<std::string>& closures,
                                       const HydroScene& hydro, const MdScene& md,
                                       const MdOutcome& md_out);

// The factor on the closure's `coefficient` (relative to the closure, as the fit's F) of the
// hydro whose case key `key` (hydro.*_factor) is multiplied by `factor`. The fit's F multiplies
// every factor key of the coefficient together, so a hydro with one of them at f is the grid's
// hydro at F = f for a coefficient of that key alone (shear_viscosity), and for
// effective_conductivity its kappa - mu n/T is (f kappa - mu n/T) or (kappa - f mu n/T) over the
// closure's: the value of the closure with the injection over that without, each at the
// homogeneous state (n = T = 1; the ratio does not depend on T for hard disks). A
// pressure-balanced mode sees the heat flux -(kappa - mu n/T) dT/dx alone (dn/dx = -(n/T)
// dT/dx, docs/physics.md §15), so to linear order that hydro's mode decays as the grid's at this
// F. A key outside the coefficient (hydro.cooling_factor, or hydro.viscosity_factor for a
// conductivity) gives 1: the fit measures the coefficient, not it.
double injected_coefficient_factor(const std::string& coefficient, const HydroScene& hydro,
                                   const std::string& key, double factor);

}  // namespace granvv::app
