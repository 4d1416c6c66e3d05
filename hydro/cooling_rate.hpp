#pragma once
// The inelastic loss of the cooling term (physics.cooling; docs/physics.md §9). Kinetic theory
// of smooth inelastic disks cools at a rate proportional to 1 - r^2 = 4q(1 - q) (r = 1 - 2q);
// the paper's 8q/K keeps its small-q limit 4q. "exact" multiplies the cooling term of any
// closure by (1 - q).
#include <string>
#include <vector>

namespace granvv::hydro {

enum class CoolingRate { small_q, exact };

// The names the case accepts ("small_q", "exact") and the conversions. from_name throws
// std::invalid_argument for another name, listing the known ones.
std::vector<std::string> cooling_rate_names();
CoolingRate cooling_rate_from_name(const std::string& name);
std::string to_string(CoolingRate cooling);

// (1 - r^2) / (4q): 1 for "small_q", 1 - q for "exact".
double inelastic_loss_factor(CoolingRate cooling, double q);

}  // namespace granvv::hydro
