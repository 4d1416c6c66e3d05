// Speed of the continuum engine, as figures: wall time and cell-steps/s of the paper's
// single-mode scene (cases/single_mode.toml) and clustering scene (cases/clustering.toml) run to
// n_max = 1e6, and of the scheme's building blocks; the single mode and one step also with the
// Enskog closure (docs/physics.md §9), whose cost per cell-step the target bounds by 1.5 times the
// dilute one. Run: build/granvv_bench (add --benchmark_repetitions=5 for spread).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "hydro/integrator.hpp"
#include "hydro/periodic_tridiagonal.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"

namespace {

using granvv::app::CaseConfig;

// A shipped scene without its convergence study and output times; cells = 0: the case's own.
granvv::app::HydroScene scene_of(const std::string& name, int cells,
                                 std::vector<std::string> sets = {}) {
  sets.insert(sets.end(), {"convergence.cells=[]", "hydro.output_times=[]"});
  if (cells > 0) sets.push_back("hydro.cells=" + std::to_string(cells));
  return granvv::app::hydro_scene_from(
      CaseConfig::from_file(std::string(GRANVV_SOURCE_DIR) + "/cases/" + name + ".toml", sets));
}

// The single-mode scene of the hydro's speed target: the step controls it was measured with
// (253 steps on 2000 cells), so that figures stay comparable across changes of the defaults.
const std::vector<std::string> kSpeedTargetSteps = {"hydro.cfl=2", "hydro.dt_max=0.05",
                                                    "hydro.max_compression=0.1"};

granvv::app::HydroScene single_mode_scene(int cells, std::vector<std::string> sets = {}) {
  sets.insert(sets.end(), kSpeedTargetSteps.begin(), kSpeedTargetSteps.end());
  return scene_of("single_mode", cells, sets);
}

// The Enskog closure on the same single mode: phi0 = 1e-7 keeps the peak below freezing up to
// n_max = 1e6 (phi = 0.1 there), so both closures follow the same flow to the same stop and the
// figures compare the cost of one cell-step (the factors cost the same at any phi).
const std::vector<std::string> kEnskog = {"hydro.closure=enskog", "physics.area_fraction=1e-7"};

// A scene run to its singularity (n_max = 1e6).
void ToSingularity(benchmark::State& state, const granvv::app::HydroScene& scene) {
  const auto closure = granvv::app::make_hydro_closure(scene);
  const auto fields = granvv::hydro::make_initial_fields(scene.initial, *closure);
  long long steps = 0;
  double tau = 0;
  for (auto _ : state) {
    auto initial = granvv::hydro::discretize(fields, scene.cells, scene.node_offset, false);
    const auto run = granvv::hydro::run_hydro(*closure, std::move(initial), scene.control);
    steps = run.steps;
    tau = run.series.t.back();
    benchmark::DoNotOptimize(run.series.n_max.back());
  }
  state.counters["steps"] = double(steps);
  state.counters["t_stop"] = tau;
  state.counters["cell_steps_per_s"] = benchmark::Counter(
      double(steps) * scene.cells * state.iterations(), benchmark::Counter::kIsRate);
}
// The acceptance benchmark: single mode, 2000 cells, to the singularity.
void SingleModeToSingularity(benchmark::State& state) {
  ToSingularity(state, single_mode_scene(static_cast<int>(state.range(0))));
}
BENCHMARK(SingleModeToSingularity)->Arg(1000)->Arg(2000)->Arg(4000)->Unit(benchmark::kMillisecond);
// The same with the Enskog closure.
void SingleModeEnskogToSingularity(benchmark::State& state) {
  ToSingularity(state, single_mode_scene(static_cast<int>(state.range(0)), kEnskog));
}
BENCHMARK(SingleModeEnskogToSingularity)->Arg(2000)->Unit(benchmark::kMillisecond);

// The shipped single-mode scene as it is (its own cells and step controls).
void SingleModeAsShipped(benchmark::State& state) {
  ToSingularity(state, scene_of("single_mode", 0));
}
BENCHMARK(SingleModeAsShipped)->Unit(benchmark::kMillisecond);

// Paper Figs. 1-2, as shipped: 300 random modes cluster until the major peak's singularity.
void ClusteringToSingularity(benchmark::State& state) {
  ToSingularity(state, scene_of("clustering", 0));
}
BENCHMARK(ClusteringToSingularity)->Unit(benchmark::kMillisecond);

// One predictor-corrector step with Strang-split cooling on the initial single-mode state.
void IntegratorStep(benchmark::State& state, std::vector<std::string> sets) {
  const auto scene = single_mode_scene(static_cast<int>(state.range(0)), std::move(sets));
  const auto closure = granvv::app::make_hydro_closure(scene);
  auto s = granvv::hydro::discretize(granvv::hydro::make_initial_fields(scene.initial, *closure),
                                     scene.cells, 0.5, false);
  granvv::hydro::HydroIntegrator integrator(*closure, scene.cells);
  for (auto _ : state) {
    auto copy = s;
    benchmark::DoNotOptimize(integrator.step(copy, 1e-5).accepted);
  }
  state.counters["cell_steps_per_s"] =
      benchmark::Counter(double(scene.cells) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(IntegratorStep, dilute, std::vector<std::string>{})
    ->Arg(2000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(IntegratorStep, enskog, kEnskog)->Arg(2000)->Unit(benchmark::kMicrosecond);

// One factorisation and solve of a periodic tridiagonal SPD system (LAPACK dpttrf/dpttrs and the
// Sherman-Morrison corner).
void PeriodicTridiagonal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  granvv::hydro::PeriodicTridiagonalSolver solver(n);
  std::vector<double> diag(n, 4.0), upper(n, -1.0), rhs(n, 1.0), x;
  for (auto _ : state) {
    solver.factorize(diag, upper);
    solver.solve(rhs, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["unknowns_per_s"] =
      benchmark::Counter(double(n) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(PeriodicTridiagonal)->Arg(2000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
