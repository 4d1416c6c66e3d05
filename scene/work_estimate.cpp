#include "scene/work_estimate.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace granvv::app {

namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

double machine_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
}

int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {  // Open MPI, MPICH
    if (const char* value = std::getenv(name)) {
      const int n = std::atoi(value);
      if (n > 0) return n;
    }
  }
  return 1;
}

std::string human_duration(double seconds) {
  if (!std::isfinite(seconds)) return "forever";
  if (seconds < 120.0) return number(seconds) + " s";
  if (seconds < 7200.0) return number(seconds / 60.0) + " min";
  if (seconds < 172800.0) return number(seconds / 3600.0) + " h";
  return number(seconds / 86400.0) + " days";
}

std::string ParticleRunEstimate::describe() const {
  return "per rank (" + std::to_string(ranks) + (ranks == 1 ? " rank" : " ranks") +
         "): " + number(work_per_rank) + " " + unit + ", " + number(bytes_per_rank / 1e9) +
         " GB of memory (this machine has " + number(machine_bytes / 1e9) + " GB), about " +
         human_duration(seconds()) + " of wall time at the measured " + number(rate) + " " + unit +
         "/s per core";
}

double ParticleRunEstimate::member_share_done(double t, double t_end) const {
  if (member_work_until) {
    const double whole = member_work_until(t_end);
    if (whole > 0.0 && std::isfinite(whole)) return member_work_until(t) / whole;
  }
  return t_end > 0.0 ? t / t_end : 1.0;
}

double ParticleRunEstimate::seconds_left(int member, int ensemble, int jobs, double share_done,
                                         double wall_seconds) const {
  const double f = std::clamp(share_done, 1e-9, 1.0);
  const int later = std::max(0, ensemble - 1 - member) / std::max(1, member_groups);
  return wall_seconds * (1.0 - f) / f + wall_seconds / f * later / std::max(1, jobs);
}

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
                   double limit, const std::string& unit, const std::string& what,
                   const std::string& remedy) {
  if (std::isfinite(estimate) && estimate <= limit) return;
  const std::string key = key_to_blame(c, keys);
  const std::string origin = c.origin(key);
  throw ConfigError((origin == "default" ? c.source() : origin) + ": " + key + " = " +
                    abbreviated(format_value(c.value(key)), 80) + ": " + what + " needs about " +
                    number(estimate) + " " + unit + "; the limit is " + number(limit) + " " + unit +
                    (remedy.empty() ? " (a run that cannot finish here)" : "; " + remedy));
}

}  // namespace granvv::app
