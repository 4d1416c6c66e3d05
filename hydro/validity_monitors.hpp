#pragma once
// Validity monitors of a hydro run (docs/physics.md §9, "Validity monitors"): per state, the
// largest local value of each dimensionless number whose smallness the hydrodynamics assumes,
// and where it is largest. In the scaled units of docs/physics.md §1, with chi the contact value
// the closure uses (1 for the dilute gas, Henderson's chi(phi0 n) for the dense one):
//   mean free path   l   = (sqrt(2 pi)/8) K / (n chi)
//   collision time   tau = K / (4 n chi T^{1/2})
//   area fraction        phi = phi0 n
//   Knudsen numbers      l |d ln n/dx|,  l |dv/dx| / T^{1/2},  l |d ln T/dx|
//   collision / flow     tau |dv/dx|
// Velocity gradients are those of the cells (between their nodes); density and temperature
// gradients those of the nodes (between their cells), with l the mean of the two cells'.
#include <array>
#include <optional>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

enum class Monitor : int {
  area_fraction,
  knudsen_density,
  knudsen_velocity,
  knudsen_temperature,
  collision_flow
};
inline constexpr int kMonitors = 5;

// The thresholds past which the gradient expansion of the hydrodynamics is not trusted: its
// first neglected terms are of relative size Kn (resp. tau |dv/dx|), so 0.1 is a 10 % error.
// The area fraction's threshold belongs to the closure (ValidityScales::area_fraction_limit).
inline constexpr double kKnudsenThreshold = 0.1;
inline constexpr double kCollisionFlowThreshold = 0.1;

struct MonitorDefinition {
  Monitor monitor;
  const char* name;     // key in summary.json hydro.validity
  const char* column;   // column of the hydro time series (hydro/time_series.hpp)
  const char* meaning;  // what it measures
};
// In the order of Monitor.
const std::array<MonitorDefinition, kMonitors>& monitor_definitions();

// The monitors' thresholds for a closure's scales, in the order of Monitor.
std::array<double, kMonitors> monitor_thresholds(const ValidityScales& scales);
// Whether a monitor can be evaluated: the area fraction needs phi0.
bool monitor_applies(Monitor m, const ValidityScales& scales);

struct MonitorValue {
  double value = 0.0;  // the largest over the mesh (0 where the monitor does not apply)
  double x = 0.0;      // where, wrapped into [-1/2, 1/2)
};
using ValidityMeasures = std::array<MonitorValue, kMonitors>;

// Per-cell values of the monitors, kept between calls so that a run measuring every step
// allocates them once.
struct ValidityWorkspace {
  std::vector<double> inverse_collisions, flow, density_jump, temperature_jump;
};

// The monitors of state s (cells: its widths and densities, measure_cells).
ValidityMeasures measure_validity(const LagrangianState& s, const CellGeometry& cells,
                                  const ValidityScales& scales, ValidityWorkspace& work);
ValidityMeasures measure_validity(const LagrangianState& s, const CellGeometry& cells,
                                  const ValidityScales& scales);

// The first state at which a monitor reached its threshold.
struct MonitorCrossing {
  double value = 0.0, time = 0.0, x = 0.0;
};

// A run's monitors: thresholds, first crossings and the largest values seen.
struct ValidityRecord {
  std::array<double, kMonitors> threshold{};
  std::array<bool, kMonitors> applies{};
  std::array<std::optional<MonitorCrossing>, kMonitors> first_crossing;
  std::array<double, kMonitors> largest{};

  explicit ValidityRecord(const ValidityScales& scales = {});
  // The measures of the state at time t.
  void note(const ValidityMeasures& measures, double t);
};

}  // namespace granvv::hydro
