// An atlas's scene, observables and injected errors from its case (atlas/atlas_setup.hpp).
#include "atlas/atlas_setup.hpp"

#include <algorithm>

#include "atlas/atlas_analysis.hpp"
#include "atlas/detectable_error.hpp"
#include "compare/transport_coefficients.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "models/compare_scene.hpp"
#include "models/model.hpp"
#include "models/setting_run.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {
namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> items;
  std::string item;
  for (char c : s + ",") {
    if (c == ',') {
      if (!item.empty()) items.push_back(item);
      item.clear();
    } else if (c != ' ') {
      item += c;
    }
  }
  return items;
}

// atlas.observables, expanded: "scene" by the scene's type, "crossing_times" into one name per
// crossing level below the stop density.
std::vector<std::string> judged_observables(const CaseConfig& c, bool homogeneous, bool particles,
                                            const std::vector<double>& levels) {
  const std::string text = c.string("atlas.observables");
  std::vector<std::string> asked = split_list(text);
  if (asked.empty()) {
    throw ConfigError(c.origin("atlas.observables") + ": atlas.observables = \"" + text +
                      "\": give \"scene\" or one or more of " +
                      join(atlas_observable_names(), ", "));
  }
  if (asked == std::vector<std::string>{"scene"}) {
    asked = !homogeneous
                ? std::vector<std::string>{"crossing_times", "thermal_energy", "kinetic_energy",
                                           "field_n",        "field_v_x",      "field_T"}
            : particles ? std::vector<std::string>{"thermal_energy", "haff_t0"}
                        : std::vector<std::string>{"thermal_energy"};
  }
  std::vector<std::string> names;
  for (const auto& a : asked) {
    const auto& allowed = atlas_observable_names();
    if (std::find(allowed.begin(), allowed.end(), a) == allowed.end()) {
      throw ConfigError(c.origin("atlas.observables") + ": atlas.observables = \"" + text +
                        "\": '" + a + "' is not an observable; allowed: scene, or " +
                        join(allowed, ", "));
    }
    if (a == "crossing_times") {
      for (double level : levels) names.push_back(crossing_time_name(level));
    } else {
      names.push_back(a);
    }
  }
  return names;
}

}  // namespace

AtlasSetup atlas_setup(const std::string& case_name, const std::vector<std::string>& sets) {
  AtlasSetup setup;
  AtlasScene& scene = setup.scene;
  scene.source = locate_case(case_name);
  scene.sets = sets;
  scene.config = std::make_shared<const CaseConfig>(
      CaseConfig::from_string(scene.source.text, scene.source.origin, scene.sets));
  const CaseConfig& config = *scene.config;
  refuse_keys_of_models_not_run(config, RunningCommand::atlas);
  const HydroScene hydro = hydro_scene_from(config);
  scene.case_hydro = std::make_shared<const HydroScene>(hydro);
  scene.name = config.name();
  scene.particles = config.boolean("md.enabled");
  scene.bins = config.int_value("atlas.bins");
  scene.sigmas = config.real("compare.sigmas");
  scene.agreement_fraction = config.real("compare.agreement_fraction");
  if (scene.particles) {
    // Every model is compared on the particles' bins: their ensemble mean has its error there.
    const int md_bins = config.int_value("md.bins");
    if (config.origin("atlas.bins") != "default" && scene.bins != md_bins) {
      throw ConfigError(config.origin("atlas.bins") +
                        ": atlas.bins = " + std::to_string(scene.bins) +
                        ": a particle scene is compared on md.bins = " + std::to_string(md_bins) +
                        "; leave atlas.bins unset or equal to it");
    }
    scene.bins = md_bins;
    const std::optional<MdScene> md = md_scene_from(config, hydro);
    scene.particle_count = md->spec.scene.particles;
    scene.md_t_end = md->spec.t_end;
    scene.md_t_haff =
        md::haff_time_md(md->spec.scene, md::enskog_chi(md->spec.scene.area_fraction));
    scene.t0_theory = md->spec.scene.scaled_time(scene.md_t_haff);
    scene.signal_to_noise = initial_signal_to_noise(*md).ratio();
  }
  if (const auto compare = compare_scene_from(config);
      compare && compare->transport &&
      !compare::find_transport_pair(compare->transport->coefficient) &&
      !compare::find_transport_flux_fit(compare->transport->coefficient)) {
    scene.transport_coefficient = compare->transport->coefficient;
  }
  const std::string initial_type = hydro.initial.type;
  scene.has_inertia_reference = hydro::inertia_reference(hydro.initial).has_value();
  const double stop_density = hydro.control.stop_density;
  for (double level : hydro.control.crossing_densities) {
    if (level < stop_density && initial_type != "uniform") scene.crossing_levels.push_back(level);
  }
  setup.observables =
      judged_observables(config, initial_type == "uniform", scene.particles, scene.crossing_levels);
  setup.injected_errors = config.reals("atlas.injected_errors");
  if (setup.injected_errors.empty()) setup.injected_errors = atlas::default_injected_errors();
  // The compared times: the hydro's own output times, or those of a particle scene.
  const HydroScene aligned = atlas_hydro_scene(config, scene);
  scene.times = aligned.control.output_times;
  if (scene.times.empty()) scene.times.push_back(aligned.control.t_end);
  return setup;
}

}  // namespace granvv::app
