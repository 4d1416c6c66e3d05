#pragma once
// A rung of the ladder of models (docs/architecture.md, "Model families"): everything that
// differs between the Haff ODE, flow by inertia, the hydro with each closure and the particles
// with each engine is declared by its family, once: its name and place on the ladder, when it
// applies to a scene (and why not), its knobs (their case keys, the atlas's default grid, how
// cost scales with them), its failure modes, its style in the report, and how it runs a
// setting. The atlas and `granvv run` ask the families; nothing else branches on a model's name.
//
// The families are made from the closure and engine registries (hydro/closure_registry.cpp,
// md_bridge/particle_engine_registry.cpp), so registering a closure or an engine adds its rung.
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "models/model_setting.hpp"

namespace granvv::app {

// How a family's runs stand to the truth, which decides how the atlas treats them:
// - exact: a closed-form solution, one run, no knob;
// - discretised: deterministic with numerical knobs; its finest run is its own reference and
//   its error the difference to its neighbours one step coarser;
// - ensemble: stochastic; its error is the scatter of its members.
enum class FamilyKind { exact, discretised, ensemble };

// A cost knob: its name in a setting (and in atlas.json and atlas.h5), how its value is written
// (an integer, a real or a flag) and its value in atlas.h5 for a run of a family without it.
struct KnobSpec {
  enum class Type { integer, real, flag };
  std::string name;
  Type type = Type::real;
  double absent = 0.0;
  // Left out of a setting's description when it has its absent value (a factor of 1).
  bool quiet_when_absent = false;
};

// The knob every ensemble family has: its size, md.ensemble (models/particle_family.hpp).
inline constexpr const char* kEnsembleKnob = "ensemble";
// The contact knobs of a family with a contact map (has_contact_map): md.max_overlap,
// md.steps_per_contact and md.adaptive_stiffness (models/family_lammps.cpp, atlas/dem_map.cpp).
inline constexpr const char* kMaxOverlapKnob = "max_overlap";
inline constexpr const char* kStepsPerContactKnob = "steps_per_contact";
inline constexpr const char* kAdaptiveStiffnessKnob = "adaptive_stiffness";

// How the report draws the family (matplotlib colour and marker), written to atlas.json.
struct ModelStyle {
  std::string color;
  std::string marker;
};

// A knob the stability search pushes from the case's own setting, by this factor per push.
struct KnobPush {
  std::string knob;
  double factor = 1.0;
};

class ModelFamily {
 public:
  explicit ModelFamily(std::string name) : name_(std::move(name)) {}
  virtual ~ModelFamily() = default;
  const std::string& name() const { return name_; }
  virtual FamilyKind kind() const = 0;
  virtual ModelStyle style() const = 0;
  virtual std::vector<KnobSpec> knobs() const { return {}; }

  // Why the family cannot answer the scene; nullopt where it applies.
  virtual std::optional<std::string> not_applicable(const AtlasScene&) const {
    return std::nullopt;
  }
  // The case's own setting, and the first run the atlas makes of the family (its cost calibrates
  // the estimates of the others): the case's own setting unless the family says otherwise.
  virtual AtlasSetting case_setting(const AtlasScene& scene) const;
  virtual AtlasSetting pilot(const AtlasScene& scene) const { return case_setting(scene); }
  // The atlas's grid of settings (its atlas.* keys, else its default grid around the case).
  virtual std::vector<AtlasSetting> grid(const AtlasScene&) const { return {}; }
  // Whether the setting is planned before the rest of the grid (the rest go cheapest first): a
  // discretised family's finest corner (its reference), an engine's own contact.
  virtual bool plan_first(const AtlasSetting&, const AtlasScene&) const { return false; }
  // A setting's estimated wall seconds from the pilot's. The family works out what it needs of
  // the pilot once, when the atlas plans its grid; the estimate refers to the scene, which must
  // outlive it.
  using CostEstimate = std::function<double(const AtlasSetting&)>;
  virtual CostEstimate estimate(const AtlasRun& pilot, const AtlasScene&) const {
    return [seconds = pilot.cost.wall_seconds](const AtlasSetting&) { return seconds; };
  }
  // Whether a is a finer setting than b: the finest finished run is the family's own reference.
  virtual bool finer(const AtlasSetting&, const AtlasSetting&) const { return false; }
  // Whether a run of the setting can be a reference (it is of the case's own scene).
  virtual bool may_be_reference(const AtlasSetting&) const { return true; }
  // A discretised family: whether run is a neighbour one step coarser of reference in one knob.
  virtual bool coarser_neighbour(const AtlasSetting&, const AtlasSetting&) const { return false; }
  // The knobs the stability search pushes (empty: none), and the setting with one knob changed.
  virtual std::vector<KnobPush> stability_pushes() const { return {}; }
  AtlasSetting with_knob(AtlasSetting setting, const std::string& knob, double value) const;
  // Whether the case itself runs this family (its own closure, its own engine).
  virtual bool is_case_model(const AtlasScene&) const { return false; }
  // The keys of the model errors the comparison power can inject (in the family's case table;
  // empty: none).
  virtual std::vector<std::string> injected_error_keys() const { return {}; }
  // Whether the family's runs of the scene keep their transport fit (AtlasRun::transport): the
  // particle axis of the comparison power on a scene that measures a coefficient.
  virtual bool keeps_transport_fit(const AtlasScene&) const { return false; }
  // Whether the atlas maps the bias of its contact knobs against the hard disks (DEM map).
  virtual bool has_contact_map() const { return false; }
  // Whether the case runs runs of this family on threads (particle engines call MPI: in turn).
  virtual bool runs_on_threads() const { return kind() != FamilyKind::ensemble; }

  // The --set overrides that make the setting from the case (after the user's).
  virtual std::vector<std::string> overrides(const AtlasScene&, const AtlasSetting&) const {
    return {};
  }
  // Runs the setting of the resolved case `config` into run (status, cost, fields, scalars). A
  // ConfigError means the scene refuses the setting; Interrupted, a signal; any other exception
  // is the family's to turn into a failure status or to let through.
  virtual void run(const AtlasScene& scene, const CaseConfig& config, AtlasRun& run) const = 0;
  // Failure modes judged on a finished run, also when it came from the cache (so that a limit
  // set by an [atlas] key can change without running it again).
  virtual void judge(const AtlasScene&, AtlasRun&) const {}

  // "hydro/dilute cells=500 step_factor=1", "particles/event_driven ensemble=16".
  std::string describe(const AtlasSetting& setting) const;
  // The setting's knobs as atlas.json gives them, each of its type; and with its model.
  nlohmann::json knobs_json(const AtlasSetting& setting) const;
  nlohmann::json setting_json(const AtlasSetting& setting) const;

 private:
  std::string name_;
};

// Every family, poorest first (the ladder's order): the exact solutions, the hydro with each
// registered closure, the particles with each registered engine.
const std::vector<const ModelFamily*>& model_families();
// The family of that name; std::invalid_argument naming the known ones.
const ModelFamily& model_family(const std::string& name);
// Its place on the ladder (0: the poorest).
int ladder_rank(const std::string& name);
// Every knob of every family once, in the ladder's order (the columns of atlas.h5).
std::vector<KnobSpec> all_knobs();

// The --set overrides that make `setting` from the case: the user's, then the family's.
std::vector<std::string> setting_overrides(const AtlasScene& scene, const AtlasSetting& setting);
// The setting's resolved case; ConfigError where the schema or the scene refuses it.
CaseConfig setting_case(const AtlasScene& scene, const AtlasSetting& setting);

// The family's description and JSON of a setting, by its model's name.
std::string describe(const AtlasSetting& setting);
nlohmann::json setting_json(const AtlasSetting& setting);

}  // namespace granvv::app
