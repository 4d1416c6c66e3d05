#include "atlas/atlas_power.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "atlas/detectable_error.hpp"
#include "compare/side_by_side.hpp"
#include "models/transport_measurement.hpp"
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

// The factor on the scene's fitted coefficient of each injected hydro (per key and direction, one
// per eps; models/transport_measurement.hpp), and the keys that move it.
struct InjectedFactors {
  json factors = json::object();
  std::vector<std::string> judged;
};

InjectedFactors injected_factors(const AtlasScene& scene, const std::vector<std::string>& keys,
                                 const std::vector<double>& epsilons) {
  InjectedFactors out;
  for (const auto& key : keys) {
    bool moves = false;
    for (const Direction d : kDirections) {
      json row = json::array();
      for (double eps : epsilons) {
        const double f = injected_coefficient_factor(scene.transport_coefficient, *scene.case_hydro,
                                                     "hydro." + key, injected_factor(eps, d.sign));
        moves |= f != 1.0;
        row.push_back(f);
      }
      out.factors[key][d.name] = row;
    }
    if (moves) out.judged.push_back(key);
  }
  return out;
}

// One particle run's transport fit and what it catches of each injected error.
json transport_fit_row(const AtlasScene& scene, const AtlasRun& particles,
                       const InjectedFactors& injected, const std::vector<std::string>& keys,
                       const std::vector<double>& epsilons) {
  if (!particles.transport) return {{"failure", "the run kept no transport fit"}};
  const AtlasTransportFit& t = *particles.transport;
  // A fit at the end of its factor grid does not bracket F (its error is not F's): no fit.
  const bool fitted = t.failure.empty() && !t.at_grid_edge && std::isfinite(t.factor) &&
                      std::isfinite(t.error) && t.error > 0.0;
  json detectable = json::object(), verdicts = json::object();
  for (const auto& key : keys) {
    const bool judged =
        std::find(injected.judged.begin(), injected.judged.end(), key) != injected.judged.end();
    for (const Direction d : kDirections) {
      std::vector<bool> caught, finished;
      json marks = json::array();
      for (std::size_t i = 0; i < epsilons.size(); ++i) {
        const double f = injected.factors[key][d.name][i].get<double>();
        finished.push_back(fitted && judged);
        caught.push_back(finished.back() &&
                         atlas::catches_by_transport_fit(t.factor, t.error, f, scene.sigmas));
        marks.push_back(!judged         ? "not_judged"
                        : !fitted       ? "no_fit"
                        : caught.back() ? "caught"
                                        : "missed");
      }
      const auto from = atlas::smallest_detectable(epsilons, caught, finished);
      detectable[key][d.name] = from ? json(*from) : json(nullptr);
      verdicts[key][d.name] = marks;
    }
  }
  return {{"factor", number_or_null(t.factor)},
          {"error", number_or_null(t.error)},
          {"chi2", number_or_null(t.chi2)},
          {"degrees_of_freedom", t.degrees_of_freedom},
          {"at_grid_edge", t.at_grid_edge},
          {"wall_seconds", t.wall_seconds},
          {"failure", t.failure.empty() ? json(nullptr) : json(t.failure)},
          {"unperturbed_off",
           fitted ? json(atlas::off_by_transport_fit(t.factor, t.error, 1.0, scene.sigmas))
                  : json(nullptr)},
          {"unperturbed_pull", fitted ? json((1.0 - t.factor) / t.error) : json(nullptr)},
          {"detectable", detectable},
          {"verdicts", verdicts}};
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
  const bool fits = !scene.transport_coefficient.empty();
  const InjectedFactors injected =
      fits ? injected_factors(scene, hydro.injected_error_keys(), epsilons) : InjectedFactors{};
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
    json row = {{"setting", setting_json(p->setting)},
                {"wall_seconds", p->cost.wall_seconds},
                {"work", p->cost.work},
                {"work_unit", p->cost.work_unit},
                {"unperturbed",
                 {{"disagreement", compare::disagreement_name(base_kind)},
                  {"finished", base.finished},
                  {"agreed_throughout", base.agreed_throughout},
                  {"agreed_until", base.agreed_until ? json(*base.agreed_until) : json(nullptr)}}},
                {"detectable", detectable},
                {"verdicts", verdicts}};
    if (fits) {
      row["transport_fit"] =
          transport_fit_row(scene, *p, injected, hydro.injected_error_keys(), epsilons);
    }
    rows.push_back(row);
  }
  json power = {
      {"hydro", setting_json(unperturbed.setting)},
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
  if (fits) {
    power["transport_fit"] = {
        {"coefficient", scene.transport_coefficient},
        {"injected_factors", injected.factors},
        {"keys_judged", injected.judged},
        {"how",
         "at each particle run the factor F on the closure's coefficient is fitted to the "
         "members' k = 1 mode with its jackknife standard error, as granvv run fits it; an "
         "injected hydro's factor is its coefficient over the closure's; an eps is caught when "
         "the injected hydro is more than compare.sigmas standard errors from F while the "
         "unperturbed closure (factor 1) is not (unperturbed_off: it is, and nothing is "
         "caught); a fit that failed or ended at the edge of its factor grid judges nothing "
         "(no_fit); keys that do not move the coefficient are not judged"}};
  }
  return power;
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
