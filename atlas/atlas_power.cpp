#include "atlas/atlas_power.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "atlas/detectable_error.hpp"
#include "compare/side_by_side.hpp"
#include "scene/case_schema.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
using nlohmann::json;

namespace {

// The two directions of an injected error: the coefficient made larger and smaller.
struct Direction {
  const char* name;
  double sign;
};
constexpr Direction kDirections[] = {{"up", 1.0}, {"down", -1.0}};

double injected_factor(double eps, double sign) {
  return std::pow(1.0 + eps, sign);
}

// One hydro judged against one particle run, as `granvv run` judges its comparison.
atlas::JudgedHydro judge(const AtlasScene& scene, const AtlasRun& hydro, const AtlasRun& particles,
                         compare::Disagreement* kind = nullptr) {
  atlas::JudgedHydro j;
  if (hydro.status != "ok" || !hydro.fields || !particles.fields ||
      hydro.times.size() != scene.times.size()) {
    return j;
  }
  const compare::VerdictRule rule{compare::kClearSignalToNoise, scene.sigmas};
  const compare::SideBySide s = compare::judge_side_by_side(
      *particles.fields, *hydro.fields, compare::compared_fields(scene.case_hydro->transverse),
      scene.sigmas, scene.agreement_fraction, scene.signal_to_noise, rule);
  j.finished = true;
  j.model_disagreement = s.kind == compare::Disagreement::model_clear_signal ||
                         s.kind == compare::Disagreement::model_box_offset;
  j.agreed_throughout = s.window.throughout;
  j.agreed_until = s.window.until;
  if (kind) *kind = s.kind;
  return j;
}

}  // namespace

std::vector<AtlasSetting> comparison_power_settings(const ModelFamily& hydro,
                                                    const AtlasScene& scene,
                                                    const std::vector<double>& epsilons) {
  std::vector<AtlasSetting> settings;
  for (const auto& key : hydro.injected_error_keys()) {
    for (const Direction d : kDirections) {
      for (double eps : epsilons) {
        AtlasSetting s = hydro.case_setting(scene);
        s.injected = key;
        s.injected_factor = injected_factor(eps, d.sign);
        settings.push_back(s);
      }
    }
  }
  return settings;
}

json comparison_power(const ModelFamily& hydro, const AtlasScene& scene,
                      const AtlasRun& unperturbed, const std::vector<AtlasRun>& hydro_runs,
                      const std::vector<const AtlasRun*>& particle_runs,
                      const std::vector<double>& epsilons) {
  auto find_run = [&](const std::string& key, double factor) -> const AtlasRun* {
    for (const auto& r : hydro_runs) {
      if (r.setting.injected == key && r.setting.injected_factor == factor) return &r;
    }
    return nullptr;
  };
  json rows = json::array();
  for (const AtlasRun* p : particle_runs) {
    compare::Disagreement base_kind = compare::Disagreement::none;
    const atlas::JudgedHydro base = judge(scene, unperturbed, *p, &base_kind);
    json detectable = json::object(), verdicts = json::object();
    for (const auto& key : hydro.injected_error_keys()) {
      for (const Direction d : kDirections) {
        std::vector<bool> caught, finished;
        json marks = json::array();
        for (double eps : epsilons) {
          const AtlasRun* h = find_run(key, injected_factor(eps, d.sign));
          const atlas::JudgedHydro j = h ? judge(scene, *h, *p) : atlas::JudgedHydro{};
          finished.push_back(j.finished);
          caught.push_back(atlas::catches_injected_error(j, base));
          marks.push_back(!j.finished ? "not_run" : caught.back() ? "caught" : "missed");
        }
        const auto from = atlas::smallest_detectable(epsilons, caught, finished);
        detectable[key][d.name] = from ? json(*from) : json(nullptr);
        verdicts[key][d.name] = marks;
      }
    }
    rows.push_back(
        {{"setting", setting_json(p->setting)},
         {"wall_seconds", p->cost.wall_seconds},
         {"work", p->cost.work},
         {"work_unit", p->cost.work_unit},
         {"unperturbed",
          {{"disagreement", compare::disagreement_name(base_kind)},
           {"finished", base.finished},
           {"agreed_throughout", base.agreed_throughout},
           {"agreed_until", base.agreed_until ? json(*base.agreed_until) : json(nullptr)}}},
         {"detectable", detectable},
         {"verdicts", verdicts}});
  }
  return {{"hydro", setting_json(unperturbed.setting)},
          {"keys", hydro.injected_error_keys()},
          {"epsilons", epsilons},
          {"directions", {"up: the coefficient times (1 + eps)", "down: divided by (1 + eps)"}},
          {"signal_to_noise", number_or_null(scene.signal_to_noise)},
          {"disks_per_member", scene.particle_count},
          {"how",
           "each injected hydro is judged side by side against each particle run as granvv run "
           "judges its comparison (compare.sigmas, compare.agreement_fraction, the verdict "
           "rule); an eps is caught when the verdict is a model disagreement that the "
           "unperturbed hydro does not have (an earlier parting, or any parting where it "
           "agreed throughout); detectable is the smallest eps from which every larger one is "
           "caught"},
          {"particles", rows}};
}

// The comparison power within its share of the budget (atlas/atlas_power.hpp): the eps grid is
// thinned to every other value until its hydro runs fit, and skipped with the reason if even
// two values do not.
json comparison_power_within_budget(const AtlasScene& scene, const std::vector<AtlasRun>& runs,
                                    const ModelFamily& reference_family,
                                    std::vector<double> epsilons, BudgetShares& budget, int jobs,
                                    AtlasRunner& runner, double total_budget) {
  // The hydro the case itself runs, at its own setting, takes the injected errors.
  const ModelFamily* hydro = nullptr;
  for (const ModelFamily* f : model_families()) {
    if (f->kind() == FamilyKind::discretised && f->is_case_model(scene)) hydro = f;
  }
  const AtlasRun* unperturbed = nullptr;
  std::vector<const AtlasRun*> particle_runs;
  const AtlasSetting own_particles = reference_family.case_setting(scene);
  for (const auto& r : runs) {
    if (hydro && r.setting == hydro->case_setting(scene)) unperturbed = &r;
    // The reference's runs at the case's own setting but for the ensemble size.
    const bool own_setting =
        reference_family.with_knob(r.setting, kEnsembleKnob, own_particles.knob(kEnsembleKnob)) ==
        own_particles;
    if (r.setting.model == reference_family.name() && r.status == "ok" && r.fields && own_setting) {
      particle_runs.push_back(&r);
    }
  }
  std::stable_sort(particle_runs.begin(), particle_runs.end(),
                   [](const AtlasRun* a, const AtlasRun* b) {
                     return a->setting.knob(kEnsembleKnob) < b->setting.knob(kEnsembleKnob);
                   });
  const double share = budget.share();
  budget.done();
  if (!unperturbed || unperturbed->status != "ok") {
    return {{"skipped", "the case's own hydro (" +
                            (hydro ? hydro->name() : "closure " + scene.case_hydro->closure) +
                            ") did not finish, so there is nothing to inject errors into"}};
  }
  const double each = std::max(unperturbed->cost.wall_seconds, 1e-3);
  const std::size_t per_eps = comparison_power_settings(*hydro, scene, {1.0}).size();
  auto estimate_of = [&](std::size_t n) { return each * double(per_eps * n) / jobs; };
  int thinned = 0;
  while (epsilons.size() > 2 && estimate_of(epsilons.size()) > share) {
    std::vector<double> kept;
    for (std::size_t i = 0; i < epsilons.size(); i += 2) kept.push_back(epsilons[i]);
    epsilons = kept;
    ++thinned;
  }
  if (estimate_of(epsilons.size()) > share) {
    return {{"skipped", "its " + std::to_string(per_eps * epsilons.size()) +
                            " hydro runs, estimated " + format_real(estimate_of(epsilons.size())) +
                            " s, would pass its share of the budget (" + format_real(share) +
                            " s of --budget " + format_real(total_budget) + ")"}};
  }
  const std::vector<AtlasSetting> settings = comparison_power_settings(*hydro, scene, epsilons);
  const std::vector<AtlasRun> hydro_runs =
      runner.run(settings, std::vector<double>(settings.size(), each));
  budget.spend(estimate_of(epsilons.size()));
  json power = comparison_power(*hydro, scene, *unperturbed, hydro_runs, particle_runs, epsilons);
  power["thinned"] = thinned;  // times the default grid was halved to fit the budget
  return power;
}

}  // namespace granvv::app
