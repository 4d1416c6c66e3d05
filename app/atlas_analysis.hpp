#pragma once
// How far one atlas run is from another (docs/atlas.md, "What it measures"): the relative error
// of each judged observable, and the error over the scene's time axis that the ladder timeline
// draws. The reference is a model's own finest run (numerical error) or the richest model's
// (model error).
#include <map>
#include <string>
#include <vector>

#include "app/atlas_runs.hpp"

namespace granvv::app {

// The observables an atlas can judge (atlas.observables), "crossing_times" standing for one
// crossing_time_n<level> per level of the scene.
const std::vector<std::string>& atlas_observable_names();

// Relative error per observable name (expanded: crossing_time_n10, ..., thermal_energy,
// kinetic_energy, field_n, field_v_x, field_T):
// - a crossing time: |t / t_ref - 1|;
// - an energy per particle: the largest relative error over the reference's compared times;
// - a field: the largest rms difference over the bins and those times, on the field's physical
//   scale (compare/model_comparison.hpp: n in n0, v in the thermal speed, T in the mean T).
// An observable the run does not give at every one of those times is left out: the run is not
// adequate for it.
std::map<std::string, double> observable_errors(const AtlasRun& run, const AtlasRun& reference,
                                                const std::vector<std::string>& observables);

// The observables among `observables` that the run's model gives at all (flow by inertia has
// no temperature, the Haff ODE no crossing times).
std::vector<std::string> provided_observables(const AtlasRun& run,
                                              const std::vector<std::string>& observables);

// At each of the reference's compared times, the largest error of the time-resolved observables
// (energies and fields) among `observables`; NaN where the run has no value there.
std::vector<double> error_over_time(const AtlasRun& run, const AtlasRun& reference,
                                    const std::vector<std::string>& observables);

}  // namespace granvv::app
