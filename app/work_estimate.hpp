#pragma once
// The work a case asks for, estimated before anything runs (steps, cell-steps, atom-steps,
// output size), and the limits beyond which a run cannot finish here and is refused with one
// line naming the key, its value and the estimate.
#include <initializer_list>
#include <string>
#include <vector>

#include "app/case_config.hpp"

namespace granvv::app {

// Hydro: 1e12 cell-steps is about two days at the measured 6e6 cell-steps/s (README).
constexpr double kMaxCellSteps = 1e12;
// Particles: each engine's own limit (md_bridge/particle_work.hpp).
// Particle runs in segments (one per sample or snapshot), each a LAMMPS `run` with its log
// header of about 1 kB: 1e7 segments is a 10 GB log.
constexpr double kMaxSegments = 1e7;
// Particle frames (H5MD) and time series: at most 20 GB on disk.
constexpr double kMaxOutputBytes = 2e10;

// Of `keys`, the one the user set last: a --set before the case file before a default (the
// first of equals). The key a refusal names.
std::string key_to_blame(const CaseConfig& config, std::initializer_list<std::string> keys);
std::string key_to_blame(const CaseConfig& config, const std::vector<std::string>& keys);

// Throws ConfigError "ORIGIN: KEY = VALUE: <what> (estimate E); the limit is L <unit>" if
// estimate > limit or is not finite; KEY is key_to_blame(keys).
void refuse_beyond(const CaseConfig& config, std::initializer_list<std::string> keys,
                   double estimate, double limit, const std::string& unit, const std::string& what);
void refuse_beyond(const CaseConfig& config, const std::vector<std::string>& keys, double estimate,
                   double limit, const std::string& unit, const std::string& what);

}  // namespace granvv::app
