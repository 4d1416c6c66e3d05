#pragma once
// kappa and mu measured at their definition from a scene's particle ensemble (docs/physics.md
// §14, "The heat flux at its definition"; compare/heat_flux_fit.hpp), with no hydro in the fit,
// every value relative to the elastic dilute coefficient of hard disks and beside each closure's.
#include <string>
#include <utility>
#include <vector>

#include "compare/heat_flux_fit.hpp"
#include "compare/transport_coefficients.hpp"
#include "models/compare_scene.hpp"

namespace granvv::app {

struct HeatFluxMeasurement {
  compare::TransportFluxFit kind;
  std::string closure;    // hydro.closure
  std::vector<double> t;  // the fitted snapshots' scaled times
  compare::HeatFluxFit fit;
  bool contact_transfer = false;  // the flux includes the contact transfer (compare/heat_flux_fit)
  // conductivity, mu and the Burnett term, in that order: measured value and error, and each
  // closure of compare.closures with its value (0 for the Burnett term: no closure has it).
  struct Coefficient {
    std::string name;
    double measured = 0.0, error = 0.0;
    std::vector<std::pair<std::string, double>> closures;
  };
  std::vector<Coefficient> coefficients;
};

// From compare.transport_start on (the first snapshot of a run started from a Maxwellian carries
// no heat flux yet: a case skips it). Throws std::runtime_error, naming compare.transport, when
// the members or snapshots are too few or the scene's temperature and density modes are
// proportional.
HeatFluxMeasurement measure_heat_flux(const compare::TransportFluxFit& kind,
                                      const CompareScene::Transport& transport,
                                      const std::vector<std::string>& closures,
                                      const HydroScene& hydro, const MdScene& md,
                                      const MdOutcome& md_out);

}  // namespace granvv::app
