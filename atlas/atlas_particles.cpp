#include "atlas/atlas_particles.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "atlas/particle_cost.hpp"
#include "atlas/recommendation.hpp"
#include "atlas/relative_bias.hpp"
#include "atlas/work_precision.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
using nlohmann::json;

namespace {

atlas::ContactKnobs knobs_of(const AtlasSetting& s) {
  return {s.ensemble, s.max_overlap, s.steps_per_contact, s.adaptive_stiffness};
}

double scalar(const AtlasRun& r, const std::string& name, bool error = false) {
  const auto& m = error ? r.scalar_errors : r.scalars;
  const auto it = m.find(name);
  return it == m.end() ? atlas::kNoValue : it->second;
}

// The bias of one scalar of run against the hard disks' as {bias, error} JSON (null: none).
void put_bias(json& point, const std::string& key, const AtlasRun& run, const AtlasRun* hard,
              const std::string& name) {
  const atlas::RelativeBias b =
      hard ? atlas::relative_bias(scalar(run, name), scalar(run, name, true), scalar(*hard, name),
                                  scalar(*hard, name, true))
           : atlas::RelativeBias{atlas::kNoValue, atlas::kNoValue};
  point[key + "_bias"] = number_or_null(b.value);
  point[key + "_bias_error"] = number_or_null(b.error);
}

}  // namespace

std::vector<AtlasSetting> event_driven_grid(const std::vector<int>& ensembles,
                                            const std::vector<double>& particle_factors,
                                            int case_ensemble) {
  std::vector<AtlasSetting> grid;
  auto add = [&](int m, double f) {
    AtlasSetting s;
    s.model = "particles/event_driven";
    s.ensemble = m;
    s.particle_factor = f;
    grid.push_back(s);
  };
  for (int m : ensembles) add(m, 1.0);
  for (double f : particle_factors) {
    if (f != 1.0) add(case_ensemble, f);
  }
  return grid;
}

std::vector<AtlasSetting> lammps_grid(const AtlasScene& scene,
                                      const std::vector<double>& max_overlaps,
                                      const std::vector<int>& steps_per_contacts) {
  std::vector<AtlasSetting> grid;
  auto add = [&](double overlap, int spc, bool adaptive) {
    AtlasSetting s;
    s.model = "particles/lammps";
    s.ensemble = scene.case_ensemble;
    s.max_overlap = overlap;
    s.steps_per_contact = spc;
    s.adaptive_stiffness = adaptive;
    grid.push_back(s);
  };
  for (double overlap : max_overlaps) {
    for (int spc : steps_per_contacts) add(overlap, spc, scene.case_adaptive_stiffness);
  }
  for (double overlap : max_overlaps) {
    add(overlap, scene.case_steps_per_contact, !scene.case_adaptive_stiffness);
  }
  return grid;
}

AtlasSetting particle_pilot(const AtlasScene& scene, const std::string& model) {
  AtlasSetting s;
  s.model = model;
  s.ensemble = 1;
  if (is_lammps(model)) {
    s.max_overlap = scene.case_max_overlap;
    s.steps_per_contact = scene.case_steps_per_contact;
    s.adaptive_stiffness = scene.case_adaptive_stiffness;
  }
  return s;
}

double particle_estimate(const AtlasSetting& s, const AtlasRun& pilot, const AtlasScene& scene) {
  const double wall = std::max(pilot.cost.wall_seconds, 1e-3);
  // The hard disks' work is their collisions: proportional to members times particles.
  if (!is_lammps(s.model)) {
    return wall * double(s.ensemble) * s.particle_factor /
           (std::max(1, pilot.setting.ensemble) * pilot.setting.particle_factor);
  }
  return wall * atlas::dem_work_ratio(knobs_of(s), knobs_of(pilot.setting), scene.md_t_end,
                                      scene.md_t_haff);
}

bool finer_particle_run(const AtlasSetting& a, const AtlasSetting& b) {
  // Tuples compare in order: larger ensemble, smaller overlap, more steps, fixed stiffness.
  return std::make_tuple(a.ensemble, -a.max_overlap, a.steps_per_contact, !a.adaptive_stiffness) >
         std::make_tuple(b.ensemble, -b.max_overlap, b.steps_per_contact, !b.adaptive_stiffness);
}

json dem_map(const AtlasScene& scene, const std::vector<AtlasRun>& runs,
             const std::vector<ObservableErrors>& model_error,
             const std::vector<std::string>& observables, const AtlasRun* hard_disks,
             double t0_theory, double tolerance, double sigmas) {
  // The largest ensemble at each contact setting.
  std::map<std::tuple<double, int, bool>, std::size_t> chosen;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const AtlasSetting& s = runs[i].setting;
    if (!is_lammps(s.model) || runs[i].status == "refused" || runs[i].status == "interrupted") {
      continue;
    }
    const auto key = std::make_tuple(s.max_overlap, s.steps_per_contact, s.adaptive_stiffness);
    const auto it = chosen.find(key);
    if (it == chosen.end() || s.ensemble > runs[it->second].setting.ensemble) chosen[key] = i;
  }
  json points = json::array();
  std::map<std::tuple<double, int, bool>, std::string> state_at;
  for (const auto& [key, i] : chosen) {
    const AtlasRun& r = runs[i];
    std::string state = r.status;
    if (r.status == "ok") {
      state = "ok";
      const ObservableErrors t0_only =
          hard_disks ? observable_errors(r, *hard_disks, {"haff_t0"}) : ObservableErrors{};
      const auto t0e = t0_only.find("haff_t0");
      if (t0e != t0_only.end() &&
          !atlas::within_tolerance(t0e->second.error, t0e->second.reference_error, tolerance,
                                   sigmas)) {
        state = "t0_bias_above_tolerance";
      } else if (!atlas::adequate({r.cost.wall_seconds, errors_of(model_error[i]),
                                   reference_errors_of(model_error[i])},
                                  observables, tolerance, sigmas)) {
        state = "error_above_tolerance";
      }
    }
    state_at[key] = state;
    json p = {{"max_overlap", r.setting.max_overlap},
              {"steps_per_contact", r.setting.steps_per_contact},
              {"adaptive_stiffness", r.setting.adaptive_stiffness},
              {"ensemble", r.setting.ensemble},
              {"state", state},
              {"wall_seconds", r.cost.wall_seconds},
              {"work", r.cost.work},
              {"work_unit", r.cost.work_unit},
              {"haff_t0", number_or_null(scalar(r, "haff_t0"))},
              {"haff_t0_error", number_or_null(scalar(r, "haff_t0", true))},
              {"compressibility", number_or_null(scalar(r, "compressibility"))},
              {"compressibility_error", number_or_null(scalar(r, "compressibility", true))}};
    put_bias(p, "t0", r, hard_disks, "haff_t0");
    put_bias(p, "pressure", r, hard_disks, "pressure");
    put_bias(p, "compressibility", r, hard_disks, "compressibility");
    p["t0_bias_kinetic_theory"] = number_or_null(
        atlas::relative_bias(scalar(r, "haff_t0"), scalar(r, "haff_t0", true), t0_theory, 0.0)
            .value);
    points.push_back(p);
  }
  // Boundaries along each knob from the case's own contact: the grid's points in the push
  // direction, the last that is ok and the first that is not.
  json boundaries = json::array();
  const auto own = std::make_tuple(scene.case_max_overlap, scene.case_steps_per_contact,
                                   scene.case_adaptive_stiffness);
  for (const bool overlap_knob : {true, false}) {
    const char* knob = overlap_knob ? "max_overlap" : "steps_per_contact";
    json b = {{"knob", knob}, {"direction", overlap_knob ? "up" : "down"}};
    if (!state_at.count(own)) {
      b["note"] = "the case's own contact did not run";
    } else if (state_at[own] != "ok") {
      b["note"] = "the case's own contact already fails (" + state_at[own] +
                  "); no boundary along the grid";
    } else {
      std::vector<std::pair<double, std::string>> line;  // knob value, state; push order
      for (const auto& [key, state] : state_at) {
        const auto& [ov, spc, adaptive] = key;
        if (adaptive != scene.case_adaptive_stiffness) continue;
        if (overlap_knob && spc == scene.case_steps_per_contact && ov >= scene.case_max_overlap) {
          line.push_back({ov, state});
        }
        if (!overlap_knob && ov == scene.case_max_overlap && spc <= scene.case_steps_per_contact) {
          line.push_back({double(spc), state});
        }
      }
      std::sort(line.begin(), line.end());
      if (!overlap_knob) std::reverse(line.begin(), line.end());
      double stable = line.front().first;
      json failed = nullptr, failure = nullptr;
      for (const auto& [value, state] : line) {
        if (state != "ok") {
          failed = value, failure = state;
          break;
        }
        stable = value;
      }
      b.update({{"stable", stable}, {"failed", failed}, {"failure", failure}});
    }
    boundaries.push_back(b);
  }
  json against = nullptr;
  if (hard_disks) {
    against = {
        {"setting", describe(hard_disks->setting)},
        {"haff_t0", number_or_null(scalar(*hard_disks, "haff_t0"))},
        {"haff_t0_error", number_or_null(scalar(*hard_disks, "haff_t0", true))},
        {"pressure", number_or_null(scalar(*hard_disks, "pressure"))},
        {"compressibility", number_or_null(scalar(*hard_disks, "compressibility"))},
        {"compressibility_error", number_or_null(scalar(*hard_disks, "compressibility", true))}};
  }
  return {{"against", against},
          {"t0_kinetic_theory", number_or_null(t0_theory)},
          {"default",
           {{"max_overlap", scene.case_max_overlap},
            {"steps_per_contact", scene.case_steps_per_contact},
            {"adaptive_stiffness", scene.case_adaptive_stiffness}}},
          {"points", points},
          {"boundaries", boundaries}};
}

}  // namespace granvv::app
