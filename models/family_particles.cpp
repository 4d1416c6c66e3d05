// The particle families (models/particle_family.hpp): the ensemble of any registered engine, its
// run reduced to what the atlas judges, and the table of engines that have a family of their own.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>

#include "compare/ensemble_statistics.hpp"
#include "compare/model_comparison.hpp"
#include "models/families.hpp"
#include "models/model.hpp"
#include "models/particle_family.hpp"
#include "models/setting_run.hpp"
#include "models/transport_measurement.hpp"
#include "scene/case_config.hpp"
#include "scene/interruption.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {
namespace {

// The default ensemble sizes of the grid (docs/atlas.md).
const std::vector<int> kEnsembleKnobs = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
// The colour and marker of an engine without a family of its own.
const ModelStyle kPlainStyle = {"C9", "X"};

// The ensemble standard errors of the box energies at the kept times: the scatter of the
// members' own box energies (each member's snapshot j is the mean's snapshot j,
// compare/ensemble_fields.hpp). Energies per particle are the same in MD and scaled units.
void take_energy_errors(const AtlasScene& scene, const fields::ModelResult& r,
                        const MdOutcome& outcome, AtlasRun& run) {
  if (!r.fields) return;
  std::size_t k = 0;
  for (const auto& [i, j] : compare::common_snapshots(compared_times(scene), *r.fields)) {
    (void)i;
    std::vector<std::vector<double>> thermal, flow;
    for (const auto& member : outcome.runs) {
      if (j >= member.fields.snapshots.size()) continue;
      const compare::EnergiesPerParticle e = snapshot_energies(member.fields.snapshots[j]);
      thermal.push_back({e.thermal});
      flow.push_back({e.flow});
    }
    if (!thermal.empty()) {
      run.thermal_error[k] = compare::ensemble_statistics(thermal).standard_error[0];
      run.flow_error[k] = compare::ensemble_statistics(flow).standard_error[0];
    }
    ++k;
  }
}

// An engine without a contact virial in the box pressure (the event-driven one: its collisional
// transfer is the series value collision_virial_pressure, the mean over the interval since the
// previous sample) gets its pressure here, as the kinetic n0 T plus that transfer, with T the
// mean of the interval's two ends (the gas cools during it): P/(n0 T0) and P/(n0 T) averaged
// over each member's samples, then their mean and standard error over the members.
void take_collisional_pressure(const MdScene& md, const MdOutcome& outcome, AtlasRun& run) {
  if (std::isfinite(run.scalars["pressure"])) return;
  const double n0 = md.spec.scene.number_density();
  std::vector<std::vector<double>> pressure, compressibility;
  for (const auto& member : outcome.runs) {
    const auto& series = member.series;
    const std::vector<double>* transfer = nullptr;
    for (const auto& [name, values] : series.engine) {
      if (name == "collision_virial_pressure") transfer = &values;
    }
    if (!transfer || transfer->size() != series.T.size() || series.T.size() < 2) return;
    double p = 0.0, z = 0.0;
    for (std::size_t s = 1; s < series.T.size(); ++s) {
      const double T = 0.5 * (series.T[s - 1] + series.T[s]);
      p += (n0 * T + (*transfer)[s]) / n0;
      z += 1.0 + (*transfer)[s] / (n0 * T);
    }
    pressure.push_back({p / double(series.T.size() - 1)});
    compressibility.push_back({z / double(series.T.size() - 1)});
  }
  const auto p = compare::ensemble_statistics(pressure);
  const auto z = compare::ensemble_statistics(compressibility);
  run.scalars["pressure"] = p.mean[0], run.scalar_errors["pressure"] = p.standard_error[0];
  run.scalars["compressibility"] = z.mean[0];
  run.scalar_errors["compressibility"] = z.standard_error[0];
}

// The scene's transport fit on this run's members, as `granvv run` makes it: the comparison's
// hydro (from the members' t = 0 fields where the case says so) on the fit's factor grid. A fit
// that cannot be made is kept with why.
AtlasTransportFit fit_transport(const CaseConfig& config, const MdScene& md,
                                const MdOutcome& outcome) {
  const auto start = std::chrono::steady_clock::now();
  const std::optional<CompareScene> compare = compare_scene_from(config);
  AtlasTransportFit fit;
  if (!compare || !compare->transport) {
    fit.failure = "the setting's case measures no transport coefficient";
    return fit;
  }
  fit.coefficient = compare->transport->coefficient;
  try {
    HydroScene hydro = hydro_scene_from(config);
    prepare_comparison_hydro(hydro, *compare, md, outcome.fields);
    const TransportMeasurement m =
        measure_transport(*compare->transport, {hydro.closure}, hydro, md, outcome);
    fit.factor = m.fit.factor;
    fit.error = m.fit.error;
    fit.chi2 = m.fit.chi2;
    fit.degrees_of_freedom = m.fit.degrees_of_freedom;
    fit.at_grid_edge = m.fit.at_grid_edge;
  } catch (const std::exception& e) {  // too few members or snapshots, a failed grid hydro
    fit.failure = e.what();
  }
  fit.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return fit;
}

// A particle run that threw, in the atlas's failure names (models/model_setting.hpp).
std::string particle_failure(const std::string& what) {
  if (what.find("misses md.restitution") != std::string::npos) return "restitution_check_missed";
  if (what.find("event-rate runaway") != std::string::npos) return "event_rate_runaway";
  return "engine_failed";
}

}  // namespace

std::vector<KnobSpec> ParticleFamily::knobs() const {
  return {{kEnsembleKnob, KnobSpec::Type::integer, 0.0}};
}

std::optional<std::string> ParticleFamily::not_applicable(const AtlasScene& scene) const {
  if (scene.particles) return std::nullopt;
  return "md.enabled = false";
}

bool ParticleFamily::is_case_model(const AtlasScene& scene) const {
  return scene.particles && scene.config->string("md.engine") == engine_;
}

bool ParticleFamily::keeps_transport_fit(const AtlasScene& scene) const {
  return is_case_model(scene) && !scene.transport_coefficient.empty();
}

AtlasSetting ParticleFamily::case_setting(const AtlasScene& scene) const {
  AtlasSetting s;
  s.model = name();
  s.knobs[kEnsembleKnob] = double(scene.config->int_value("md.ensemble"));
  return s;
}

AtlasSetting ParticleFamily::pilot(const AtlasScene& scene) const {
  return with_knob(case_setting(scene), kEnsembleKnob, 1.0);
}

std::vector<int> ParticleFamily::ensembles(const AtlasScene& scene) {
  std::vector<int> sizes;
  for (long long m : scene.config->integers("atlas.ensembles")) sizes.push_back(int(m));
  return sizes.empty() ? kEnsembleKnobs : sizes;
}

std::vector<AtlasSetting> ParticleFamily::grid(const AtlasScene& scene) const {
  std::vector<AtlasSetting> grid;
  for (int m : ensembles(scene)) grid.push_back(with_knob(case_setting(scene), kEnsembleKnob, m));
  return grid;
}

ModelFamily::CostEstimate ParticleFamily::estimate(const AtlasRun& pilot,
                                                   const AtlasScene& scene) const {
  const double seconds = std::max(pilot.cost.wall_seconds, 1e-3);
  const double pilot_work = estimated_work(scene, pilot.setting);
  return [&scene, seconds, pilot_work](const AtlasSetting& s) {
    const double work = estimated_work(scene, s);
    // A setting the scene refuses is refused at once, before it costs anything.
    if (!(work > 0.0) || !(pilot_work > 0.0)) return 0.0;
    return seconds * work / pilot_work;
  };
}

double ParticleFamily::estimated_work(const AtlasScene& scene, const AtlasSetting& s) {
  try {
    const CaseConfig config = setting_case(scene, s);
    const std::optional<MdScene> md = md_scene_from(config, hydro_scene_from(config));
    return md ? md->estimate.work_per_rank : 0.0;
  } catch (const ConfigError&) {
    return 0.0;
  }
}

bool ParticleFamily::finer(const AtlasSetting& a, const AtlasSetting& b) const {
  return a.knob(kEnsembleKnob) > b.knob(kEnsembleKnob);
}

std::vector<std::string> ParticleFamily::overrides(const AtlasScene&, const AtlasSetting& s) const {
  return {"md.engine=" + toml_quoted(engine_),
          "md.ensemble=" + std::to_string(std::lround(s.knob(kEnsembleKnob)))};
}

void ParticleFamily::run(const AtlasScene& scene, const CaseConfig& config, AtlasRun& run) const {
  try {
    const std::optional<MdScene> md = md_scene_from(config, hydro_scene_from(config));
    const auto engine = make_engine(*md, "");
    // A signal stops the run at its next sample (scene/interruption.hpp).
    ParticleModel model(*md, *engine, [](int, const md::MdProgress&) { stop_if_interrupted(); });
    fields::ModelResult r = model.run();
    // A soft-contact engine reaches a compared time to within its time step (the largest, at
    // the end of a run with adaptive stiffness): its snapshot stands for that time.
    const double slack = md->spec.scene.scaled_time(engine->time_resolution());
    for (auto& snap : r.fields->snapshots) {
      for (double t : scene.times) {
        if (std::abs(snap.t - t) <= slack) snap.t = t;
      }
    }
    take_result(scene, r, run);
    take_energy_errors(scene, r, model.outcome(), run);
    take_collisional_pressure(*md, model.outcome(), run);
    take_engine_details(model.outcome().engine_details, run);
    if (keeps_transport_fit(scene)) run.transport = fit_transport(config, *md, model.outcome());
    run.status = "ok";
  } catch (const ConfigError&) {
    throw;
  } catch (const Interrupted&) {
    throw;
  } catch (const std::runtime_error& e) {  // the engine failed: kept, it is an outcome
    const AtlasSetting setting = run.setting;
    run = AtlasRun{};
    run.setting = setting;
    run.status = particle_failure(e.what());
    run.reason = e.what();
  }
}

const ModelFamily* particle_family(const std::string& engine) {
  // The engines with a family of their own; every other registered engine gets the plain one.
  static const std::map<std::string, const ModelFamily* (*)()> own = {
      {"lammps", &lammps_family},
      {"event_driven", &event_driven_family},
      {"recorded", &recorded_family}};
  if (const auto it = own.find(engine); it != own.end()) return it->second();
  static std::deque<ParticleFamily> plain;
  for (const auto& f : plain) {
    if (f.name() == "particles/" + engine) return &f;
  }
  return &plain.emplace_back(engine, kPlainStyle);
}

}  // namespace granvv::app
