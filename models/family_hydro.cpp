// The hydro with one registered closure as a family of the ladder (models/model_family.hpp):
// discretised, with two knobs, the cells and a factor on the step bounds hydro.cfl, hydro.dt_max
// and hydro.max_compression (1 = the case's own). Its failures are the driver's stop reasons.
#include <algorithm>
#include <cmath>
#include <deque>

#include "hydro/closure.hpp"
#include "hydro/validity_monitors.hpp"
#include "models/families.hpp"
#include "models/model.hpp"
#include "models/setting_run.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"

namespace granvv::app {
namespace {

constexpr const char* kCells = "cells";
constexpr const char* kStepFactor = "step_factor";
// The default grid around the case's own setting (docs/atlas.md): cells times these, and these
// factors on the step bounds. The finest corner is the family's converged reference.
const std::vector<double> kCellFactors = {0.25, 0.5, 1.0, 2.0, 4.0, 8.0};
const std::vector<double> kStepFactors = {0.25, 0.5, 1.0, 2.0, 4.0};
// Colours and markers of the report, by the closure's place in its registry.
const std::vector<ModelStyle> kStyles = {{"C0", "o"}, {"C3", "^"}, {"C6", "<"},
                                         {"C7", ">"}, {"C8", "p"}, {"C9", "h"}};

// How a hydro run ended, in the atlas's failure names (models/model_setting.hpp).
std::string hydro_status(const HydroOutcome& out) {
  const auto& run = out.run;
  switch (run.status) {
    case hydro::RunStatus::completed:
      return "ok";
    case hydro::RunStatus::singularity:
      return run.stop_reason.find("min_cell_width") != std::string::npos ? "unresolved_singularity"
                                                                         : "ok";
    case hydro::RunStatus::closure_limit:
      return "closure_limit";
    case hydro::RunStatus::failed:
      if (run.stop_reason.find("admissible") != std::string::npos) return "inadmissible_step";
      if (run.stop_reason.find("non-finite") != std::string::npos) return "non_finite";
      return "step_underflow";
  }
  return "failed";
}

class HydroFamily : public ModelFamily {
 public:
  HydroFamily(const std::string& closure, ModelStyle style)
      : ModelFamily("hydro/" + closure), closure_(closure), style_(std::move(style)) {}
  FamilyKind kind() const override { return FamilyKind::discretised; }
  ModelStyle style() const override { return style_; }
  std::vector<KnobSpec> knobs() const override {
    return {{kCells, KnobSpec::Type::integer, 0.0}, {kStepFactor, KnobSpec::Type::real, 0.0}};
  }

  std::optional<std::string> not_applicable(const AtlasScene& scene) const override {
    if (!hydro::closure_on_every_ladder(closure_) && !is_case_model(scene)) {
      return "runs only in a case that chooses it (hydro.closure = " + toml_quoted(closure_) + ")";
    }
    HydroScene own = *scene.case_hydro;
    own.closure = closure_;
    const auto problem = hydro::closure_parameter_problem(closure_, closure_parameters(own));
    if (!problem) return std::nullopt;
    return "needs physics." + problem->parameter + ": " + problem->reason;
  }

  AtlasSetting case_setting(const AtlasScene& scene) const override {
    return setting(scene.case_hydro->cells, 1.0);
  }

  std::vector<AtlasSetting> grid(const AtlasScene& scene) const override {
    const auto [cells, factors] = grid_axes(scene);
    std::vector<AtlasSetting> settings;
    for (int c : cells) {
      for (double f : factors) {
        if (c == scene.case_hydro->cells && f == 1.0) continue;
        settings.push_back(setting(c, f));
      }
    }
    return settings;
  }
  // The finest corner of the grid (its last cells, its first step factor) is planned first.
  bool plan_first(const AtlasSetting& s, const AtlasScene& scene) const override {
    const auto [cells, factors] = grid_axes(scene);
    return s.knob(kCells) == cells.back() && s.knob(kStepFactor) == factors.front();
  }
  // The work is cells times steps, and the steps grow as the cells where the sound limit binds
  // and as 1/factor.
  CostEstimate estimate(const AtlasRun& pilot, const AtlasScene& scene) const override {
    const double seconds = std::max(pilot.cost.wall_seconds, 1e-3);
    const double case_cells = scene.case_hydro->cells;
    return [seconds, case_cells](const AtlasSetting& s) {
      const double c = s.knob(kCells) / case_cells;
      return seconds * std::max(c * c, c) / s.knob(kStepFactor);
    };
  }
  bool finer(const AtlasSetting& a, const AtlasSetting& b) const override {
    return a.knob(kCells) > b.knob(kCells) ||
           (a.knob(kCells) == b.knob(kCells) && a.knob(kStepFactor) < b.knob(kStepFactor));
  }
  bool coarser_neighbour(const AtlasSetting& r, const AtlasSetting& ref) const override {
    const double c = r.knob(kCells), c_ref = ref.knob(kCells);
    const double f = r.knob(kStepFactor), f_ref = ref.knob(kStepFactor);
    const bool coarser_cells = f == f_ref && c < c_ref && 2 * c >= c_ref;
    const bool coarser_step = c == c_ref && f > f_ref && f <= 2 * f_ref;
    return coarser_cells || coarser_step;
  }
  std::vector<KnobPush> stability_pushes() const override {
    return {{kStepFactor, 2.0}, {kCells, 0.5}};
  }
  bool is_case_model(const AtlasScene& scene) const override {
    return scene.case_hydro->closure == closure_;
  }
  // The case keys (without "hydro.") of the transport factors (hydro/transport_factors.hpp), in
  // the order the atlas gives them; mu's only for a closure with a heat flux down the density
  // gradient (elsewhere mu = 0 and its factor changes nothing).
  std::vector<std::string> injected_error_keys() const override {
    if (!hydro::closure_has_density_heat_flux(closure_)) {
      return {"viscosity_factor", "conductivity_factor", "cooling_factor"};
    }
    return {"viscosity_factor", "conductivity_factor", "mu_factor", "cooling_factor"};
  }

  std::vector<std::string> overrides(const AtlasScene& scene,
                                     const AtlasSetting& s) const override {
    const double f = s.knob(kStepFactor);
    std::vector<std::string> sets = {
        "hydro.closure=" + toml_quoted(closure_),
        "hydro.cells=" + std::to_string(std::lround(s.knob(kCells))),
        "hydro.cfl=" + format_real(scene.case_hydro->control.time_step.cfl * f),
        "hydro.dt_max=" + format_real(scene.case_hydro->control.time_step.dt_max * f),
        "hydro.max_compression=" +
            format_real(scene.case_hydro->control.time_step.max_compression * f)};
    if (!s.injected.empty()) {
      sets.push_back("hydro." + s.injected + "=" + format_real(s.injected_factor));
    }
    return sets;
  }

  void run(const AtlasScene& scene, const CaseConfig& config, AtlasRun& run) const override {
    const HydroScene hydro = atlas_hydro_scene(config, scene);
    HydroModel model(hydro, scene.bins);
    const fields::ModelResult r = model.run();
    run.status = hydro_status(model.outcome());
    run.reason = model.outcome().run.stop_reason;
    run.rejected_steps = model.outcome().run.rejected_steps;
    for (const auto& d : hydro::monitor_definitions()) {
      const auto& crossing = model.outcome().run.validity.first_crossing[int(d.monitor)];
      if (crossing) run.monitor_crossings[d.name] = crossing->time;
    }
    take_result(scene, r, run);
    time_by_fastest(run.cost, [&] { return HydroModel(hydro, scene.bins).run().cost; });
  }

 private:
  AtlasSetting setting(int cells, double step_factor) const {
    AtlasSetting s;
    s.model = name();
    s.knobs = {{kCells, double(cells)}, {kStepFactor, step_factor}};
    return s;
  }
  // atlas.cells and atlas.step_factors, else the default grid around the case's own setting.
  std::pair<std::vector<int>, std::vector<double>> grid_axes(const AtlasScene& scene) const {
    const CaseConfig& c = *scene.config;
    std::vector<int> cells;
    for (long long n : c.integers("atlas.cells")) cells.push_back(int(n));
    std::vector<double> factors = c.reals("atlas.step_factors");
    if (cells.empty()) {
      for (double f : kCellFactors) {
        const int n = std::max(4, int(std::lround(scene.case_hydro->cells * f)));
        if (cells.empty() || n > cells.back()) cells.push_back(n);
      }
    }
    if (factors.empty()) factors = kStepFactors;
    return {cells, factors};
  }

  std::string closure_;
  ModelStyle style_;
};

}  // namespace

const ModelFamily* hydro_family(const std::string& closure) {
  static std::deque<HydroFamily> families;
  for (const auto& f : families) {
    if (f.name() == "hydro/" + closure) return &f;
  }
  return &families.emplace_back(closure, kStyles[families.size() % kStyles.size()]);
}

}  // namespace granvv::app
