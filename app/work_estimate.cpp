#include "app/work_estimate.hpp"

#include <cmath>
#include <cstdio>

namespace granvv::app {

namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

std::string key_to_blame(const CaseConfig& c, std::initializer_list<std::string> keys) {
  return key_to_blame(c, std::vector<std::string>(keys));
}

std::string key_to_blame(const CaseConfig& c, const std::vector<std::string>& keys) {
  std::string best;
  int best_rank = -1;
  for (const std::string& key : keys) {
    const int rank = c.origin_precedence(key);
    if (rank > best_rank) best = key, best_rank = rank;
  }
  return best;
}

void refuse_beyond(const CaseConfig& c, std::initializer_list<std::string> keys, double estimate,
                   double limit, const std::string& unit, const std::string& what) {
  refuse_beyond(c, std::vector<std::string>(keys), estimate, limit, unit, what);
}

void refuse_beyond(const CaseConfig& c, const std::vector<std::string>& keys, double estimate,
                   double limit, const std::string& unit, const std::string& what) {
  if (std::isfinite(estimate) && estimate <= limit) return;
  const std::string key = key_to_blame(c, keys);
  const std::string origin = c.origin(key);
  throw ConfigError((origin == "default" ? c.source() : origin) + ": " + key + " = " +
                    abbreviated(format_value(c.value(key)), 80) + ": " + what + " needs about " +
                    number(estimate) + " " + unit + "; the limit is " + number(limit) + " " + unit +
                    " (a run that cannot finish here)");
}

}  // namespace granvv::app
