#pragma once
// `granvv sweep CASE --set KEY=V1,V2,... [--set OTHER=V]...`: one run of the scene per value of
// KEY (any numeric key of the case schema), each in its own folder, then sweep.json with every
// point's headline results and, for homogeneous cooling, the regression on the restitution
// coefficient (compare/cooling_sweep.hpp), and a sweep report.
#include <string>
#include <vector>

namespace granvv::app {

struct SweepOptions {
  std::string case_name;
  std::string out_dir;  // default out/<case name>-sweep-<key>
  std::vector<std::string> sets;
  bool quiet = false;
  bool report = true;
  double power_r_min = 0.7;  // the power of (1 - r^2) is fitted over r >= this
};

// Exit 0 if every point finished, 1 if any failed, 2 for bad input (nothing is run then).
int sweep_command(const SweepOptions& options);

}  // namespace granvv::app
