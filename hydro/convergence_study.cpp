#include "hydro/convergence_study.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "hydro/driver.hpp"

namespace granvv::hydro {
namespace {

// Fine node index of coarse node j: (j + o)/N = (j' + o)/(r N)  =>  j' = r j + o (r - 1).
int nested_node(int j, int ratio, double offset) {
  return ratio * j + static_cast<int>(std::lround(offset * (ratio - 1)));
}

struct LevelDifference {
  double x = 0, v = 0, n = 0, T = 0;
};

LevelDifference compare_levels(const LagrangianState& coarse, const LagrangianState& fine,
                               int ratio, double offset) {
  LevelDifference e;
  const int nc = coarse.cells(), nf = fine.cells();
  auto fine_x = [&](int j) { return j < nf ? fine.node_x[j] : fine.node_x[j - nf] + 1.0; };
  for (int j = 0; j < nc; ++j) {
    const int jf = nested_node(j, ratio, offset);
    e.x += std::abs(coarse.node_x[j] - fine_x(jf));
    e.v += std::abs(coarse.node_v[j] - fine.node_v[jf % nf]);
    double mass = 0.0, energy = 0.0;
    for (int k = 0; k < ratio; ++k) {
      const int i = (jf + k) % nf;
      mass += fine.cell_mass[i];
      energy += fine.cell_mass[i] * fine.cell_T[i];
    }
    const double width = fine_x(jf + ratio) - fine_x(jf);
    e.n += std::abs(coarse.cell_mass[j] / cell_width(coarse, j) - mass / width);
    e.T += std::abs(coarse.cell_T[j] - energy / mass);
  }
  e.x /= nc, e.v /= nc, e.n /= nc, e.T /= nc;
  return e;
}

}  // namespace

std::string convergence_mesh_problem(const std::vector<int>& cells, double node_offset) {
  for (size_t l = 0; l + 1 < cells.size(); ++l) {
    const int ratio = cells[l + 1] / cells[l];
    const double shift = node_offset * (ratio - 1);
    if (cells[l + 1] % cells[l] != 0 || std::abs(shift - std::round(shift)) > 1e-12) {
      return "meshes of " + std::to_string(cells[l]) + " and " + std::to_string(cells[l + 1]) +
             " cells do not nest with hydro.node_offset = " + std::to_string(node_offset) +
             " (each level must be an integer multiple r of the previous, with offset*(r-1) an "
             "integer: odd r for offset 0.5)";
    }
  }
  return "";
}

ConvergenceStudy run_convergence_study(const Closure& closure, const InitialFields& fields,
                                       const std::vector<int>& cells, double node_offset, double t,
                                       const TimeStepControl& base, const ConvergenceStops& stops,
                                       const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  ConvergenceStudy study;
  study.t = t;
  study.cfl = base.cfl;
  study.cells = cells;
  std::vector<LagrangianState> finals;
  for (int n : cells) {
    RunControl control;
    control.t_end = t;
    control.time_step = base;
    // Tie the step to the cell size everywhere, so that space and time errors shrink together.
    control.time_step.dt_max = std::min(base.dt_max, base.cfl / n);
    control.stop_density = stops.stop_density;
    control.min_cell_width = stops.min_cell_width;
    control.series_every = 1 << 30;
    RunResult level =
        run_hydro(closure, discretize(fields, n, node_offset, false), control, progress);
    if (level.status != RunStatus::completed) {
      throw std::runtime_error(
          "convergence study: the " + std::to_string(n) +
          "-cell level stopped at t = " + std::to_string(level.snapshots.back().state.t) +
          ", before convergence.t = " + std::to_string(t) + " (" + level.stop_reason +
          "); the study needs a smooth solution");
    }
    finals.push_back(std::move(level.snapshots.back().state));
  }
  for (size_t l = 0; l + 1 < cells.size(); ++l) {
    const auto e = compare_levels(finals[l], finals[l + 1], cells[l + 1] / cells[l], node_offset);
    study.error_x.push_back(e.x);
    study.error_v.push_back(e.v);
    study.error_n.push_back(e.n);
    study.error_T.push_back(e.T);
  }
  auto orders = [&](const std::vector<double>& err, std::vector<double>& out) {
    for (size_t l = 0; l + 1 < err.size(); ++l) {
      const double ratio = static_cast<double>(cells[l + 1]) / cells[l];
      out.push_back(std::log(err[l] / err[l + 1]) / std::log(ratio));
    }
  };
  orders(study.error_x, study.order_x);
  orders(study.error_v, study.order_v);
  orders(study.error_n, study.order_n);
  orders(study.error_T, study.order_T);
  study.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return study;
}

}  // namespace granvv::hydro
