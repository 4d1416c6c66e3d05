#pragma once
// The atlas's comparison power (docs/atlas.md): how much particle work it takes to test a
// hydro. The hydro at the case's own setting is run with each transport factor of
// hydro/transport_factors.hpp (viscosity, conductivity, cooling) multiplied by (1 + eps) and
// divided by it, over a log grid of eps; each of these hydros is judged side by side against
// every particle run of the reference engine (its ensemble sizes are the particle cost axis),
// as `granvv run` judges its comparison, and the smallest eps the comparison catches
// (atlas/detectable_error.hpp) is found for each particle cost. On a scene that measures one
// transport coefficient the same injected errors are also judged by each particle run's
// transport fit (AtlasRun::transport): the injected hydro's factor on the coefficient
// (models/transport_measurement.hpp, injected_coefficient_factor) against the fitted F ± sigma.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_budget.hpp"
#include "atlas/atlas_runner.hpp"
#include "atlas/atlas_runs.hpp"
#include "models/model_family.hpp"

namespace granvv::app {

// The hydro runs of the comparison power: the case's own setting of the family that takes the
// injected errors (ModelFamily::is_case_model) with one key at (1 + eps)^direction,
// direction +1 and -1, for every key and eps.
std::vector<AtlasSetting> comparison_power_settings(const ModelFamily& hydro,
                                                    const AtlasScene& scene,
                                                    const std::vector<double>& epsilons);

// atlas.json `comparison_power`: the unperturbed hydro's judgement against each particle run,
// and for each particle run, key and direction the verdict of every eps and the smallest eps
// caught (null: none up to the largest that finished); on a scene with a transport coefficient
// (AtlasScene::transport_coefficient) also `transport_fit`, the same by the fit. `hydro_runs`
// holds the runs of comparison_power_settings (any order; a missing or failed one counts as not
// finished).
nlohmann::json comparison_power(const ModelFamily& hydro, const AtlasScene& scene,
                                const AtlasRun& unperturbed,
                                const std::vector<AtlasRun>& hydro_runs,
                                const std::vector<const AtlasRun*>& particle_runs,
                                const std::vector<double>& epsilons);

// The comparison power within its share of the budget: the eps grid is thinned to every other
// value until its hydro runs fit, and skipped with the reason if even two values do not. The
// reference family's runs at the case's own setting but for their ensemble size are the
// particle cost axis.
nlohmann::json comparison_power_within_budget(const AtlasScene& scene,
                                              const std::vector<AtlasRun>& runs,
                                              const ModelFamily& reference_family,
                                              std::vector<double> epsilons, BudgetShares& budget,
                                              int jobs, AtlasRunner& runner, double total_budget);

}  // namespace granvv::app
