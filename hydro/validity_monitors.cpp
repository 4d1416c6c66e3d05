#include "hydro/validity_monitors.hpp"

#include <algorithm>
#include <cmath>

#include "hydro/enskog_factors.hpp"

namespace granvv::hydro {
namespace {

// l = <|c|> / nu with the 2D mean speed <|c|> = sqrt(pi T/2) and the collision frequency
// nu = 4 n chi T^{1/2} / K (docs/physics.md §9): l = (sqrt(2 pi)/8) K / (n chi).
constexpr double kMeanFreePathCoefficient = 0.31332853432887503;  // sqrt(2 pi) / 8

int index(Monitor m) {
  return static_cast<int>(m);
}

// |a - b| / ((a + b)/2): the jump of ln a across a node, to second order, without a logarithm.
double relative_jump(double a, double b) {
  return 2.0 * std::abs(a - b) / (a + b);
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

double mean_free_path(double K, double n, double chi) {
  return kMeanFreePathCoefficient * K / (n * chi);
}

double collision_time(double K, double n, double chi, double T) {
  return 0.25 * K / (n * chi * std::sqrt(T));
}

ValidityMeasures measure_validity(const LagrangianState& s, const CellGeometry& cells,
                                  const ValidityScales& scales) {
  const int N = s.cells();
  const double K = scales.K, phi0 = scales.area_fraction;
  const auto& w = cells.width;
  const auto& n = cells.density;
  auto chi_of = [&](double density) {
    return scales.contact_value ? enskog::chi(phi0 * density) : 1.0;
  };
  // Largest value of each monitor and the cell (velocity, area fraction) or node (n, T) of it.
  std::array<double, kMonitors> largest{};
  std::array<int, kMonitors> where{};
  auto keep = [&](Monitor m, double value, int at) {
    if (value > largest[index(m)]) largest[index(m)] = value, where[index(m)] = at;
  };
  // The previous cell's mean free path, starting from the periodic neighbour of cell 0.
  double previous_l = mean_free_path(K, n[N - 1], chi_of(n[N - 1]));
  for (int i = 0; i < N; ++i) {
    const int before = i == 0 ? N - 1 : i - 1;
    const int next_node = i + 1 < N ? i + 1 : 0;
    const double chi = chi_of(n[i]);
    const double l = mean_free_path(K, n[i], chi);
    const double dvdx = std::abs(s.node_v[next_node] - s.node_v[i]) / w[i];
    const double root_T = std::sqrt(s.cell_T[i]);
    keep(Monitor::area_fraction, phi0 * n[i], i);
    keep(Monitor::knudsen_velocity, l * dvdx / root_T, i);
    keep(Monitor::collision_flow, collision_time(K, n[i], chi, s.cell_T[i]) * dvdx, i);
    // Node i, between cells i - 1 and i.
    const double l_node = 0.5 * (l + previous_l);
    const double spacing = 0.5 * (w[i] + w[before]);
    keep(Monitor::knudsen_density, l_node * relative_jump(n[i], n[before]) / spacing, i);
    keep(Monitor::knudsen_temperature,
         l_node * relative_jump(s.cell_T[i], s.cell_T[before]) / spacing, i);
    previous_l = l;
  }
  ValidityMeasures out;
  for (const auto& d : monitor_definitions()) {
    const int k = index(d.monitor), at = where[k];
    const bool at_node =
        d.monitor == Monitor::knudsen_density || d.monitor == Monitor::knudsen_temperature;
    out[k].value = largest[k];
    out[k].x = wrap_position(at_node ? s.node_x[at] : cell_centre(s, at));
  }
  return out;
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
