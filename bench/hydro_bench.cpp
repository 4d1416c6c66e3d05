// Speed of the continuum engine, as figures: wall time and cell-steps/s of the paper's
// single-mode scene (cases/single_mode.toml) and clustering scene (cases/clustering.toml) run to
// n_max = 1e6, and of the scheme's building blocks; the single mode and one step also with the
// Enskog closure (docs/physics.md §9), whose cost per cell-step the target bounds by 1.5 times the
// dilute one. Run: build/granvv_bench (add --benchmark_repetitions=5 for spread).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "hydro/batched_tridiagonal.hpp"
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

// The single mode at 2000 cells with the shipped step controls and output times (the scene of the
// hydro throughput target in docs/performance.md); the counters use CPU time.
void SingleModeShippedControls(benchmark::State& state) {
  auto scene = granvv::app::hydro_scene_from(CaseConfig::from_file(
      std::string(GRANVV_SOURCE_DIR) + "/cases/single_mode.toml",
      {"convergence.cells=[]", "hydro.cells=" + std::to_string(state.range(0))}));
  ToSingularity(state, scene);
}
BENCHMARK(SingleModeShippedControls)->Arg(2000)->Unit(benchmark::kMillisecond);

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

// A random SPD periodic system shaped like the scheme's (mass term plus positive couplings
// between neighbours, two decades of spread), with a right side.
struct RandomPeriodicSystem {
  std::vector<double> diag, upper, rhs;
  explicit RandomPeriodicSystem(int n, unsigned seed) : diag(n), upper(n), rhs(n) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> decades(0.0, 2.0), unit(-1.0, 1.0);
    std::vector<double> g(n);
    for (auto& x : g) x = std::pow(10.0, decades(rng));
    for (int i = 0; i < n; ++i) {
      diag[i] = std::pow(10.0, decades(rng)) + g[i] + g[(i + n - 1) % n];
      upper[i] = -g[i];
      rhs[i] = unit(rng);
    }
  }
};

// Per-system figures: ns per system and ns per unknown for `systems` systems per iteration.
void count_systems(benchmark::State& state, int n, int systems) {
  const double solved = double(systems) * double(state.iterations());
  state.counters["ns_per_system"] =
      benchmark::Counter(solved * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ns_per_unknown"] = benchmark::Counter(
      solved * n * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// One factorisation and solve of a periodic tridiagonal SPD system with LAPACK: dpttrf, dpttrs
// for the Sherman-Morrison correction vector and dpttrs for the right side
// (hydro/periodic_tridiagonal, the test oracle).
void PeriodicTridiagonal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const RandomPeriodicSystem s(n, 1);
  granvv::hydro::PeriodicTridiagonalSolver solver(n);
  std::vector<double> x;
  for (auto _ : state) {
    solver.factorize(s.diag, s.upper);
    solver.solve(s.rhs, x);
    benchmark::DoNotOptimize(x.data());
  }
  count_systems(state, n, 1);
}
BENCHMARK(PeriodicTridiagonal)->Arg(2000)->Unit(benchmark::kMicrosecond);

// The same with the batched periodic LDL^T (hydro/batched_tridiagonal): K systems factorised in
// one interleaved sweep and each solved once. K = 2 is the scheme's case (momentum and energy
// of one pass), K = 3 with the transverse momentum.
template <std::size_t K>
void BatchedPeriodicTridiagonal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<RandomPeriodicSystem> systems;
  for (std::size_t k = 0; k < K; ++k) systems.emplace_back(n, 1 + k);
  std::array<granvv::hydro::PeriodicTridiagonalView, K> views;
  std::array<granvv::hydro::PeriodicLdlFactors, K> factors;
  std::array<granvv::hydro::PeriodicLdlFactors*, K> factor_out;
  std::array<const granvv::hydro::PeriodicLdlFactors*, K> factor_in;
  std::array<std::vector<double>, K> x;
  std::array<double*, K> solutions;
  for (std::size_t k = 0; k < K; ++k) {
    views[k] = {systems[k].diag.data(), systems[k].upper.data()};
    factor_out[k] = &factors[k];
    factor_in[k] = &factors[k];
    x[k] = systems[k].rhs;
    solutions[k] = x[k].data();
  }
  for (auto _ : state) {
    for (std::size_t k = 0; k < K; ++k)
      std::copy(systems[k].rhs.begin(), systems[k].rhs.end(), x[k].begin());
    granvv::hydro::factorize_periodic<K>(n, views, factor_out);
    granvv::hydro::solve_periodic<K>(n, factor_in, solutions);
    benchmark::DoNotOptimize(x[0].data());
  }
  count_systems(state, n, K);
}
BENCHMARK_TEMPLATE(BatchedPeriodicTridiagonal, 1)->Arg(2000)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BatchedPeriodicTridiagonal, 2)->Arg(2000)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BatchedPeriodicTridiagonal, 3)->Arg(2000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
