#include "support/engine_settings.hpp"

#include <variant>

#include "scene/case_schema.hpp"

namespace granvv::testing {

md::EngineSettings default_engine_settings(const std::string& engine) {
  (void)engine;  // every engine gets every key of [md] (scene/md_scene.cpp, md_scene_from)
  md::EngineSettings settings;
  for (const app::KeySpec& key : app::case_schema()) {
    if (key.section() != "md" || key.default_value.kind != app::Default::Kind::value) continue;
    const app::Value& v = key.default_value.value;
    if (const double* real = std::get_if<double>(&v)) settings[key.key] = *real;
    if (const long long* integer = std::get_if<long long>(&v)) settings[key.key] = double(*integer);
    if (const bool* boolean = std::get_if<bool>(&v)) settings[key.key] = *boolean ? 1.0 : 0.0;
  }
  return settings;
}

md::ParticleEngineSetup default_engine_setup(const std::string& engine,
                                             const md::ParticleScene& scene) {
  md::ParticleEngineSetup setup;
  setup.scene = scene;
  setup.settings = default_engine_settings(engine);
  return setup;
}

}  // namespace granvv::testing
