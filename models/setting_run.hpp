#pragma once
// What every family does to turn a model's result into the atlas's run (models/model_setting.hpp):
// the compared times, their energies and fields, the observables, and a fair time for runs too
// quick to time once.
#include <functional>

#include "compare/binned_energies.hpp"
#include "fields/model_result.hpp"
#include "models/model_setting.hpp"

namespace granvv::app {

struct HydroScene;
class CaseConfig;

// The hydro of the scene as the atlas runs it: without its convergence study and, in a particle
// scene, on the particles' physics and compared times (scaled units) from the case's own fields.
HydroScene atlas_hydro_scene(const CaseConfig& config, const AtlasScene& scene);

// The compared times as a series without fields, to pair a model's snapshots with.
fields::FieldSeries compared_times(const AtlasScene& scene);

// The box energies per particle of a snapshot; a T or v_y the model does not have counts as 0.
compare::EnergiesPerParticle snapshot_energies(const fields::FieldSnapshot& snapshot);

// The run's compared times, energies, fields and scalars from a model's result.
void take_result(const AtlasScene& scene, const fields::ModelResult& result, AtlasRun& run);

// A deterministic model too quick to time in one run (below 1 ms) is run again, up to 50 times
// in all, and costs its fastest run: in a run of microseconds one context switch or page fault
// would otherwise decide which model is the cheapest.
void time_by_fastest(fields::ModelCost& cost, const std::function<fields::ModelCost()>& rerun);

}  // namespace granvv::app
