#pragma once
// A case's hydro part: the engine's parameters read from the resolved case, the run, and
// the checks against the exact solutions that the case's physics admits.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fields/field_series.hpp"
#include "hydro/closure.hpp"
#include "hydro/convergence_study.hpp"
#include "hydro/driver.hpp"
#include "hydro/field_integrals.hpp"
#include "hydro/initial_conditions.hpp"
#include "hydro/linear_mode_measurement.hpp"
#include "hydro/singularity_analysis.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {

struct HydroScene {
  hydro::Physics physics;
  std::string closure;  // a registered closure (hydro/closure_registry.cpp)
  // physics.area_fraction (in a comparison: the particle scene's), 0 = not given.
  double area_fraction = 0.0;
  hydro::CoolingRate cooling = hydro::CoolingRate::small_q;
  // hydro.viscosity_factor, hydro.conductivity_factor, hydro.cooling_factor, hydro.mu_factor:
  // injected model errors (hydro/transport_factors.hpp).
  hydro::TransportFactors factors;
  // The closures' own keys (hydro/closure.hpp, ClosureKey) by name, every closure's, in
  // extra, texts and tables (physics, cooling and factors unused): each closure reads its own.
  hydro::ClosureParameters closure_settings;
  hydro::InitialParameters initial;
  // Fields to start from instead of initial.type's generator: in a comparison, the particles'
  // own coarse-grained t = 0 fields (models/compare_scene.hpp).
  std::optional<hydro::InitialFields> given_fields;
  // The case's keys; their defaults are in the case schema only (scene/case_schema.cpp).
  int cells = 0;
  double node_offset = 0.0;
  bool transverse = false;
  hydro::RunControl control;
  double progress_seconds = 0.0;
  double tau_fit_min_density = 0.0, tau_fit_max_density = 0.0;
  double profile_fit_x_min = 0.0, profile_fit_x_max = 0.0;
  double collapse_tolerance = 0.0;
  std::vector<int> convergence_cells;
  double convergence_t = 0.0;
  double convergence_cfl = 0.0;
};

// The case keys of the injected model errors and the factor of HydroScene::factors each sets,
// the one list hydro_scene_from reads them by.
const std::vector<std::pair<std::string, double hydro::TransportFactors::*>>&
transport_factor_keys();
// Sets the factor of case key `key`; throws std::invalid_argument for another key.
void set_transport_factor(HydroScene& scene, const std::string& key, double value);

// The closure's parameters and the closure itself, from the scene's physics.
hydro::ClosureParameters closure_parameters(const HydroScene& scene);
// The closures' own keys of a resolved case, every closure's, into params.extra, texts and
// tables (hydro/closure.hpp, ClosureKey).
void read_closure_keys(const CaseConfig& config, hydro::ClosureParameters& params);
// The case key of a problem closure `closure` has with its parameters: its own hydro.<name>,
// else physics.<name> (physics.area_fraction).
std::string closure_problem_key(const std::string& closure,
                                const hydro::ClosureParameterProblem& problem);
std::unique_ptr<hydro::Closure> make_hydro_closure(const HydroScene& scene);

// The initial condition of a resolved case: initial.type and its initial.* parameters.
hydro::InitialParameters initial_parameters_from(const CaseConfig& config);

// The refusal of an initial field that is not finite where it was evaluated (the hydro's cells,
// the particle sampler), naming the initial.* key it comes from and its value, one line.
ConfigError initial_field_refusal(const CaseConfig& config, const hydro::InitialFieldError& e);

// Reads the hydro parameters of a resolved case; throws ConfigError on combinations the
// engine cannot run (meshes that do not nest, fields that are negative somewhere...).
HydroScene hydro_scene_from(const CaseConfig& config);

// Throws ConfigError, naming the key the user set last among end_key, the step bounds and
// hydro.cells, if the hydro run to t_end cannot finish (scene/work_estimate.hpp): at least
// t_end / dt_max steps, and t_end over the first step's size, times the cells.
void check_hydro_work(const CaseConfig& config, const HydroScene& scene, double t_end,
                      const std::string& end_key);

struct SnapshotCheck {
  double t = 0.0;
  std::string label;
  hydro::Diagnostics diagnostics;
  std::optional<double> collapse_error;  // paper Fig. 3: max |v - v0(xi)| / |a|
  std::vector<double> xi, inertia_v0;    // xi = x - t v at nodes, and v0(xi)
};

struct HydroOutcome {
  hydro::RunResult run;
  fields::FieldSeries cell_fields;  // the snapshots on the hydro's cells (hydro/cell_fields.hpp)
  hydro::InitialFields fields;
  std::vector<SnapshotCheck> snapshots;
  std::optional<hydro::SingularityFit> singularity;
  // Blow-up time from the last two samples of 1/n_max(t) of a run stopped at the singularity
  // (hydro/blowup_extrapolation.hpp).
  std::optional<double> blowup_time;
  std::optional<hydro::ProfileSlope> profile_slope;
  double profile_slope_time = 0.0;
  std::optional<double> inertia_tau;     // flow-by-inertia singularity time of the initial v
  double haff_max_relative_error = 0.0;  // of the mass-weighted mean T against Haff's law
  std::optional<hydro::MeasuredRate> linear_rate;
  std::optional<hydro::ConvergenceStudy> convergence;
  int unstable_modes = 0, shear_unstable_modes = 0;
  // The totals of the initial cells and the integrals of the fields they were built from
  // (hydro/field_integrals.hpp): equal to round-off, the run's conservation from its first step.
  hydro::FieldTotals initial_cells, initial_given;
};

HydroOutcome run_hydro_scene(const HydroScene& scene, const hydro::ProgressCallback& progress);

}  // namespace granvv::app
