#pragma once
// How far one atlas run is from another (docs/atlas.md, "What it measures"): the relative error
// of each judged observable with the reference's own statistical error on the same scale, and
// the error over the scene's time axis that the ladder timeline draws. The reference is a
// model's own finest run (numerical error) or the richest model's (model error).
#include <map>
#include <string>
#include <vector>

#include "atlas/atlas_runs.hpp"

namespace granvv::app {

// The observables an atlas can judge (atlas.observables), "crossing_times" standing for one
// crossing_time_n<level> per level of the scene.
const std::vector<std::string>& atlas_observable_names();

// One observable's error against a reference, and the reference's statistical error on the same
// relative scale (NaN for a deterministic reference): what σ-aware adequacy weighs
// (atlas/recommendation.hpp).
struct ObservableError {
  double error = 0.0;
  double reference_error = 0.0;
};
using ObservableErrors = std::map<std::string, ObservableError>;

// Per observable name (expanded: crossing_time_n10, ..., haff_t0, thermal_energy,
// kinetic_energy, field_n, field_v_x, field_T):
// - a scalar (crossing time, Haff t0): |x / x_ref - 1|, with the reference's standard error over
//   |x_ref|;
// - an energy per particle: the largest relative error over the reference's compared times,
//   with the reference's ensemble standard error over its value at that time;
// - a field: the largest rms difference over the bins and those times, on the field's physical
//   scale (compare/model_comparison.hpp: n in n0, v in the thermal speed, T in the mean T), with
//   the rms over the bins of the reference's standard errors on that scale at that time.
// An observable the run does not give at every one of those times is left out: the run is not
// adequate for it.
ObservableErrors observable_errors(const AtlasRun& run, const AtlasRun& reference,
                                   const std::vector<std::string>& observables);
// The errors alone, and the reference errors alone, of a set.
std::map<std::string, double> errors_of(const ObservableErrors& errors);
std::map<std::string, double> reference_errors_of(const ObservableErrors& errors);

// The reference's own statistical error per observable (relative, as above): what no
// comparison with it can resolve. Empty for a deterministic reference.
std::map<std::string, double> statistical_errors(const AtlasRun& reference,
                                                 const std::vector<std::string>& observables);

// The observables among `observables` that the run's model gives at all (flow by inertia has
// no temperature, the Haff ODE no crossing times).
std::vector<std::string> provided_observables(const AtlasRun& run,
                                              const std::vector<std::string>& observables);

// At each of the reference's compared times, the largest error of the time-resolved observables
// (energies and fields) among `observables` with the reference's statistical error of that
// observable; error NaN where the run has no value there.
std::vector<ObservableError> error_over_time(const AtlasRun& run, const AtlasRun& reference,
                                             const std::vector<std::string>& observables,
                                             double sigmas);

}  // namespace granvv::app
