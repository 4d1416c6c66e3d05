#pragma once
// What an atlas weighs, made from the case before anything runs (docs/atlas.md): the scene
// every run shares, the judged observables and the comparison power's grid of injected errors.
#include <string>
#include <vector>

#include "models/model_setting.hpp"

namespace granvv::app {

struct AtlasSetup {
  AtlasScene scene;
  std::vector<std::string> observables;  // expanded (crossing_time_n<level>, ...)
  std::vector<double> injected_errors;   // atlas.injected_errors, or the default grid
};

// The case by name or path with the user's --set overrides. Throws ConfigError naming the key
// for a case or a combination the atlas cannot weigh.
AtlasSetup atlas_setup(const std::string& case_name, const std::vector<std::string>& sets);

}  // namespace granvv::app
