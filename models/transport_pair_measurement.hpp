#pragma once
// Two transport coefficients measured jointly from a scene's particle ensemble (docs/physics.md
// §14): the k = 1 amplitudes of several signals (compare.transport_signals) in every member, the
// hydro run on a grid of the two coefficients' factors, both fitted at once with their jackknife
// errors and correlation (compare/transport_pair_fit.hpp), every value relative to the elastic
// dilute coefficient of hard disks (compare/transport_coefficients.hpp).
#include <string>
#include <utility>
#include <vector>

#include "compare/transport_coefficients.hpp"
#include "compare/transport_pair_fit.hpp"
#include "models/compare_scene.hpp"

namespace granvv::app {

struct TransportPairMeasurement {
  compare::TransportPair pair;
  std::string closure;               // hydro.closure: the factors are on its coefficients
  std::vector<std::string> signals;  // "<field>:<phase>", in the fit's order
  std::vector<double> t;             // the snapshots' scaled times
  compare::FactorPairGrid grid;      // factors on the closure's two coefficients
  std::vector<compare::PairSignal> hydro_and_members;
  compare::PairFit fit;
  // Each coefficient: the factor times the closure's value and its error, relative to the
  // elastic dilute value; and each closure of compare.closures with its value, in that order.
  struct Coefficient {
    std::string name;
    double closure_value = 0.0, factor = 0.0, factor_error = 0.0, measured = 0.0, error = 0.0;
    std::vector<std::pair<std::string, double>> closures;
  };
  Coefficient first, second;
};

// As measure_transport (models/transport_measurement.hpp), for a pair. Throws
// std::runtime_error when a hydro run of the grid fails, the snapshots are too few, or the
// closure's second coefficient is zero (no factor on it can move it).
TransportPairMeasurement measure_transport_pair(const compare::TransportPair& pair,
                                                const CompareScene::Transport& transport,
                                                const std::vector<std::string>& closures,
                                                const HydroScene& hydro, const MdScene& md,
                                                const MdOutcome& md_out);

}  // namespace granvv::app
