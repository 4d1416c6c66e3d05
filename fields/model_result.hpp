#pragma once
// What every model of a scene's ladder returns (docs/architecture.md, "Models"): the Haff ODE,
// flow by inertia, the hydro with its closure and the particles with their engine each give
// their fields over time (where they have fields), named scalar observables and their cost, all
// in the hydro's scaled units (docs/physics.md §1), so that compare/ can weigh any two
// (compare/model_comparison.hpp).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fields/field_series.hpp"

namespace granvv::fields {

// Wall seconds and the model's own unit of work ("cell_steps", "atom_steps", "evaluations").
struct ModelCost {
  double wall_seconds = 0.0;
  double work = 0.0;
  std::string work_unit;
  double per_second() const { return work / wall_seconds; }
};

// A named scalar: a crossing time, a Haff time, a singularity time. Its standard error is NaN
// for a deterministic model.
struct Observable {
  std::string name;
  double value = 0.0;
  double standard_error = std::numeric_limits<double>::quiet_NaN();
};

struct ModelResult {
  std::string model;  // "haff_ode", "flow_by_inertia", "hydro/<closure>", "particles/<engine>"
  std::optional<FieldSeries> fields;
  std::vector<Observable> observables;
  ModelCost cost;

  // The observable called name, or nullptr.
  const Observable* observable(const std::string& name) const {
    for (const auto& o : observables) {
      if (o.name == name) return &o;
    }
    return nullptr;
  }
};

}  // namespace granvv::fields
