#pragma once
// One model of a scene's ladder at one setting of its knobs, the scene every setting shares, and
// what a run of it leaves (docs/atlas.md). A setting is a family (models/model_family.hpp) plus
// the values of that family's knobs; only the family reads them.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fields/model_result.hpp"
#include "scene/case_catalog.hpp"

namespace granvv::app {

class CaseConfig;
struct HydroScene;

struct AtlasSetting {
  std::string model;                    // the family's name (ModelFamily::name)
  std::map<std::string, double> knobs;  // its knobs' values by name (ModelFamily::knobs)
  // An injected model error (the comparison power): the key of one transport factor of the
  // family's model and the factor set on it; empty for every other run.
  std::string injected;
  double injected_factor = 1.0;

  // The knob's value; std::logic_error if the family has no such knob (a programming error).
  double knob(const std::string& name) const;
  bool operator==(const AtlasSetting& o) const {
    return model == o.model && knobs == o.knobs && injected == o.injected &&
           injected_factor == o.injected_factor;
  }
};

// The transport fit of a particle run (models/transport_measurement.hpp, as `granvv run` makes
// it): the factor F on the case's closure's coefficient that the particles' k = 1 mode follows,
// with its jackknife standard error; or why it could not be made.
struct AtlasTransportFit {
  std::string coefficient;  // compare.transport
  double factor = 0.0, error = 0.0, chi2 = 0.0;
  int degrees_of_freedom = 0;
  bool at_grid_edge = false;
  double wall_seconds = 0.0;  // the fit's hydro runs on its factor grid
  std::string failure;        // empty when F was fitted
};

// What the atlas keeps of a run.
struct AtlasRun {
  AtlasSetting setting;
  // "ok", or how it failed, in the words of the family's failure modes (ModelFamily::run):
  // inadmissible_step, non_finite, step_underflow, closure_limit, unresolved_singularity for a
  // hydro; restitution_check_missed, event_rate_runaway, engine_failed and the engines' own
  // (collapse_rule_active) for particles; refused (the case schema or the scene refused the
  // setting); interrupted.
  std::string status;
  std::string reason;  // the model's own words
  fields::ModelCost cost;
  long long rejected_steps = 0;
  // Named scalars with their standard errors (NaN: none): crossing_time_n<level>, haff_t0 and,
  // for the particles, pressure and compressibility (the box's P and P/(nT), averaged over the
  // samples and the members).
  std::map<std::string, double> scalars, scalar_errors;
  // The compared times the run reached, its energies per particle there (NaN where the model
  // has none: flow by inertia has no temperature) with their ensemble standard errors (NaN for
  // a deterministic model) and its fields on the atlas's bins (with the *_stderr of a particle
  // ensemble mean).
  std::vector<double> times, thermal, flow, thermal_error, flow_error;
  std::optional<fields::FieldSeries> fields;
  // A hydro's validity monitors (hydro/validity_monitors.hpp) that reached their threshold: the
  // monitor's name and the first time it did (scaled units).
  std::map<std::string, double> monitor_crossings;
  // A run of a family that keeps a transport fit for the scene (ModelFamily::keeps_transport_fit).
  std::optional<AtlasTransportFit> transport;
  bool cached = false;  // taken from the cache, not run now
  // Why a cache entry of this setting was not used (edited, damaged, or of other inputs).
  std::string cache_note;
};

// The scene an atlas weighs: the case with the user's --set overrides, and what every run shares.
struct AtlasScene {
  CaseSource source;
  std::vector<std::string> sets;  // the user's, applied before each setting's own
  std::string name;
  // The resolved case (with the user's --set): where each family reads its own case values.
  std::shared_ptr<const CaseConfig> config;
  // The case's own hydro (its closure, cells, step bounds, transverse velocity), as
  // scene/hydro_scene.hpp makes it.
  std::shared_ptr<const HydroScene> case_hydro;
  std::vector<double> times;  // compared times, scaled units
  std::vector<double> crossing_levels;
  int bins = 0;            // atlas.bins (a particle scene's md.bins)
  bool particles = false;  // md.enabled
  long long particle_count = 0;
  double md_t_end = 0.0, md_t_haff = 0.0;  // md.t_end and the kinetic-theory Haff time, MD units
  double t0_theory = 0.0;  // the Enskog kinetic-theory Haff time (with chi), scaled units
  double sigmas = 0.0;     // compare.sigmas: the allowance of σ-aware adequacy
  // What the side-by-side comparison of the comparison power needs beside the case's hydro:
  // compare.agreement_fraction and the particles' initial signal-to-noise (scene/md_scene.hpp).
  double agreement_fraction = 0.0;
  double signal_to_noise = 0.0;
  bool has_inertia_reference = false;
  // compare.transport when the case measures one coefficient by the transport fit (empty: none,
  // or a pair, which the atlas does not judge).
  std::string transport_coefficient;
};

}  // namespace granvv::app
