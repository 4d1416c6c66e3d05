// The families' shared behaviour and the ladder (models/model_family.hpp).
#include "models/model_family.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "hydro/closure.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "models/families.hpp"
#include "scene/case_config.hpp"
#include "scene/case_schema.hpp"

namespace granvv::app {

double AtlasSetting::knob(const std::string& name) const {
  const auto it = knobs.find(name);
  if (it == knobs.end()) throw std::logic_error(model + " has no knob '" + name + "'");
  return it->second;
}

AtlasSetting ModelFamily::case_setting(const AtlasScene&) const {
  AtlasSetting s;
  s.model = name();
  return s;
}

AtlasSetting ModelFamily::with_knob(AtlasSetting setting, const std::string& knob,
                                    double value) const {
  setting.knobs[knob] = value;
  return setting;
}

namespace {

std::string knob_text(const KnobSpec& k, double v) {
  char text[64];
  switch (k.type) {
    case KnobSpec::Type::integer:
      std::snprintf(text, sizeof text, "%lld", std::llround(v));
      return text;
    case KnobSpec::Type::flag:
      return v != 0.0 ? "true" : "false";
    case KnobSpec::Type::real:
      break;
  }
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

nlohmann::json knob_json(const KnobSpec& k, double v) {
  switch (k.type) {
    case KnobSpec::Type::integer:
      return std::llround(v);
    case KnobSpec::Type::flag:
      return v != 0.0;
    case KnobSpec::Type::real:
      break;
  }
  return v;
}

}  // namespace

std::string ModelFamily::describe(const AtlasSetting& setting) const {
  std::string text = setting.model;
  for (const KnobSpec& k : knobs()) {
    const double v = setting.knob(k.name);
    if (!(k.quiet_when_absent && v == k.absent)) text += " " + k.name + "=" + knob_text(k, v);
  }
  if (!setting.injected.empty()) {
    text += " " + setting.injected + "=" + format_real(setting.injected_factor);
  }
  return text;
}

nlohmann::json ModelFamily::knobs_json(const AtlasSetting& setting) const {
  nlohmann::json j = nlohmann::json::object();
  for (const KnobSpec& k : knobs()) j[k.name] = knob_json(k, setting.knob(k.name));
  return j;
}

nlohmann::json ModelFamily::setting_json(const AtlasSetting& setting) const {
  nlohmann::json j = knobs_json(setting);
  j["model"] = setting.model;
  if (!setting.injected.empty()) j[setting.injected] = setting.injected_factor;
  return j;
}

const std::vector<const ModelFamily*>& model_families() {
  static const std::vector<const ModelFamily*> ladder = [] {
    std::vector<const ModelFamily*> families = exact_families();
    for (const auto& closure : hydro::closure_names()) {
      families.push_back(hydro_family(closure));
    }
    for (const auto& engine : md::particle_engine_names()) {
      families.push_back(particle_family(engine));
    }
    return families;
  }();
  return ladder;
}

const ModelFamily& model_family(const std::string& name) {
  std::string known;
  for (const ModelFamily* f : model_families()) {
    if (f->name() == name) return *f;
    known += (known.empty() ? "" : ", ") + f->name();
  }
  throw std::invalid_argument("unknown model \"" + name + "\" (known: " + known + ")");
}

int ladder_rank(const std::string& name) {
  const auto& families = model_families();
  for (std::size_t i = 0; i < families.size(); ++i) {
    if (families[i]->name() == name) return int(i);
  }
  throw std::invalid_argument("unknown model \"" + name + "\"");
}

std::vector<KnobSpec> all_knobs() {
  std::vector<KnobSpec> all;
  for (const ModelFamily* f : model_families()) {
    for (const KnobSpec& k : f->knobs()) {
      bool seen = false;
      for (const KnobSpec& a : all) seen |= a.name == k.name;
      if (!seen) all.push_back(k);
    }
  }
  return all;
}

std::string describe(const AtlasSetting& setting) {
  return model_family(setting.model).describe(setting);
}

nlohmann::json setting_json(const AtlasSetting& setting) {
  return model_family(setting.model).setting_json(setting);
}

std::vector<std::string> setting_overrides(const AtlasScene& scene, const AtlasSetting& s) {
  std::vector<std::string> sets = scene.sets;
  for (auto& set : model_family(s.model).overrides(scene, s)) sets.push_back(std::move(set));
  return sets;
}

CaseConfig setting_case(const AtlasScene& scene, const AtlasSetting& s) {
  return CaseConfig::from_string(scene.source.text, scene.source.origin,
                                 setting_overrides(scene, s));
}

}  // namespace granvv::app
