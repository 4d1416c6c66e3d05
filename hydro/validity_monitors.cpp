#include "hydro/validity_monitors.hpp"

#include <algorithm>
#include <cmath>

#include "hydro/enskog_factors.hpp"
#include "hydro/largest_value.hpp"
#include "hydro/wide_loops.hpp"

namespace granvv::hydro {
namespace {

// l = <|c|> / nu with the 2D mean speed <|c|> = sqrt(pi T/2) and the collision frequency
// nu = 4 n chi T^{1/2} / K (docs/physics.md §9): l = (sqrt(2 pi)/8) K / (n chi).
constexpr double kMeanFreePathCoefficient = 0.31332853432887503;  // sqrt(2 pi) / 8

int index(Monitor m) {
  return static_cast<int>(m);
}

}  // namespace

const std::array<MonitorDefinition, kMonitors>& monitor_definitions() {
  static const std::array<MonitorDefinition, kMonitors> definitions{{
      {Monitor::area_fraction, "area_fraction", "phi_max",
       "largest local area fraction phi0 n (absent without phi0)"},
      {Monitor::knudsen_density, "knudsen_density", "knudsen_n_max",
       "largest Knudsen number of the density, l |d ln n/dx|"},
      {Monitor::knudsen_velocity, "knudsen_velocity", "knudsen_v_max",
       "largest Knudsen number of the velocity, l |dv/dx| / T^(1/2)"},
      {Monitor::knudsen_temperature, "knudsen_temperature", "knudsen_T_max",
       "largest Knudsen number of the temperature, l |d ln T/dx|"},
      {Monitor::collision_flow, "collision_flow", "collision_flow_max",
       "largest collision time over flow time, tau |dv/dx|"},
  }};
  return definitions;
}

std::array<double, kMonitors> monitor_thresholds(const ValidityScales& scales) {
  std::array<double, kMonitors> t{};
  t[index(Monitor::area_fraction)] = scales.area_fraction_limit;
  t[index(Monitor::knudsen_density)] = kKnudsenThreshold;
  t[index(Monitor::knudsen_velocity)] = kKnudsenThreshold;
  t[index(Monitor::knudsen_temperature)] = kKnudsenThreshold;
  t[index(Monitor::collision_flow)] = kCollisionFlowThreshold;
  return t;
}

bool monitor_applies(Monitor m, const ValidityScales& scales) {
  return m != Monitor::area_fraction || scales.area_fraction > 0.0;
}

GRANVV_WIDE_LOOPS
ValidityMeasures measure_validity(const LagrangianState& s, const CellGeometry& cells,
                                  const ValidityScales& scales, ValidityWorkspace& work) {
  const int N = s.cells();
  const double K = scales.K, phi0 = scales.area_fraction;
  const auto& w = cells.width;
  const auto& n = cells.density;
  const auto& T = s.cell_T;
  const auto& v = s.node_v;
  // Per cell, with the collision-rate factor 1/(n chi): l = (sqrt(2 pi)/8) K/(n chi), and
  // l |dv/dx| / T^{1/2} = (sqrt(2 pi)/8) g, tau |dv/dx| = g/4 with g = K |dv| / (n chi w T^{1/2}),
  // so the two velocity monitors share g and the cell where it is largest. Per node, between
  // cells b and i: l_node |jump of ln n| / spacing = [2 (l_b + l_i) / (w_i + w_b)] |n_i - n_b| /
  // (n_i + n_b), and the same with T (the bracket shared; each jump divided on its own, so that
  // equal jumps give equal values and the first node of a tie is kept). The per-cell values are
  // stored and their largest found afterwards, so that the loops with the divisions vectorise.
  auto& inverse_collisions = work.inverse_collisions;
  inverse_collisions.resize(N);
  if (scales.contact_value) {
    for (int i = 0; i < N; ++i) inverse_collisions[i] = 1.0 / (n[i] * enskog::chi(phi0 * n[i]));
  } else {
    for (int i = 0; i < N; ++i) inverse_collisions[i] = 1.0 / n[i];
  }
  work.flow.resize(N);
  work.density_jump.resize(N);
  work.temperature_jump.resize(N);
  double* flow = work.flow.data();
  double* density_jump = work.density_jump.data();
  double* temperature_jump = work.temperature_jump.data();
  const double* inverse = inverse_collisions.data();
  const double path = kMeanFreePathCoefficient * K;
  const auto measure = [&](int i, int before, int next_node) {
    const double dv = std::abs(v[next_node] - v[i]);
    const double g = K * dv * inverse[i] / (w[i] * std::sqrt(T[i]));
    flow[i] = 0.25 * g;
    const double node_scale =
        2.0 * (path * inverse[i] + path * inverse[before]) / (w[i] + w[before]);
    density_jump[i] = node_scale * (std::abs(n[i] - n[before]) / (n[i] + n[before]));
    temperature_jump[i] = node_scale * (std::abs(T[i] - T[before]) / (T[i] + T[before]));
  };
  measure(0, N - 1, 1);
#pragma GCC ivdep  // distinct arrays
  for (int i = 1; i + 1 < N; ++i) measure(i, i - 1, i + 1);
  measure(N - 1, N - 2, 0);
  std::array<LargestAt, kMonitors> largest;
  LargestAt area;
  if (phi0 != 0.0) {
    // phi0 n_i is largest where n_i is (phi0 > 0; phi0 = 0 leaves the monitor at 0); the first
    // cell holding the rounded product phi0 n_max, as a scan of phi0 n_i would find it.
    area.value = phi0 * largest_with_index(n).value;
    while (area.value > 0.0 && phi0 * n[area.at] != area.value) ++area.at;
  }
  largest[index(Monitor::area_fraction)] = area;
  largest[index(Monitor::knudsen_density)] = largest_with_index(work.density_jump);
  largest[index(Monitor::knudsen_temperature)] = largest_with_index(work.temperature_jump);
  const LargestAt flow_largest = largest_with_index(work.flow);
  largest[index(Monitor::collision_flow)] = flow_largest;
  // l |dv/dx| / T^{1/2} = (sqrt(2 pi)/8) g = sqrt(pi/2) tau |dv/dx|, at the same cell.
  largest[index(Monitor::knudsen_velocity)] = {
      kMeanFreePathCoefficient * (4.0 * flow_largest.value), flow_largest.at};
  ValidityMeasures out;
  for (const auto& d : monitor_definitions()) {
    const int k = index(d.monitor), at = largest[k].at;
    const bool at_node =
        d.monitor == Monitor::knudsen_density || d.monitor == Monitor::knudsen_temperature;
    out[k].value = largest[k].value;
    out[k].x = wrap_position(at_node ? s.node_x[at] : cell_centre(s, at));
  }
  return out;
}

ValidityMeasures measure_validity(const LagrangianState& s, const CellGeometry& cells,
                                  const ValidityScales& scales) {
  ValidityWorkspace work;
  return measure_validity(s, cells, scales, work);
}

ValidityRecord::ValidityRecord(const ValidityScales& scales)
    : threshold(monitor_thresholds(scales)) {
  for (const auto& d : monitor_definitions()) {
    applies[index(d.monitor)] = monitor_applies(d.monitor, scales);
  }
}

void ValidityRecord::note(const ValidityMeasures& measures, double t) {
  for (int k = 0; k < kMonitors; ++k) {
    if (!applies[k]) continue;
    largest[k] = std::max(largest[k], measures[k].value);
    if (!first_crossing[k] && measures[k].value >= threshold[k]) {
      first_crossing[k] = MonitorCrossing{measures[k].value, t, measures[k].x};
    }
  }
}

}  // namespace granvv::hydro
