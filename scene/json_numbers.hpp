#pragma once
// summary.json convention (docs/outputs.md): numbers are numbers, absent results are null.
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

namespace granvv::app {

inline nlohmann::json number_or_null(std::optional<double> v) {
  return v && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// A verdict, or null when there is nothing to judge.
inline nlohmann::json bool_or_null(std::optional<bool> v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

}  // namespace granvv::app
