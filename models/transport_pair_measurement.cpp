#include "models/transport_pair_measurement.hpp"

#include <cmath>
#include <stdexcept>

#include "compare/mode_amplitudes.hpp"
#include "models/model.hpp"
#include "models/transport_measurement.hpp"

namespace granvv::app {
TransportPairMeasurement measure_transport_pair(const compare::TransportPair& pair,
                                                const CompareScene::Transport& transport,
                                                const std::vector<std::string>& closures,
                                                const HydroScene& hydro, const MdScene& md,
                                                const MdOutcome& md_out) {
  const compare::TransportCoefficient& first = compare::transport_coefficient(pair.first);
  const compare::TransportCoefficient& second = compare::transport_coefficient(pair.second);
  TransportPairMeasurement out;
  out.pair = pair;
  out.closure = hydro.closure;
  out.first.name = pair.first;
  out.second.name = pair.second;
  out.first.closure_value = closure_coefficient_value(first, hydro, hydro.closure);
  out.second.closure_value = closure_coefficient_value(second, hydro, hydro.closure);
  if (out.second.closure_value == 0.0) {
    throw std::runtime_error("transport: the " + hydro.closure + " closure's " + pair.second +
                             " is zero, so no factor on it can be fitted (hydro.closure: one "
                             "with " +
                             pair.second + ", e.g. garzo_dufty)");
  }
  out.grid.factors_a = transport.factors;
  for (double v : pair.second_values) out.grid.factors_b.push_back(v / out.second.closure_value);
  // One grid step below the first (mu = 0): a measured mu near zero keeps its error.
  out.grid.b_below = out.grid.factors_b[1] - out.grid.factors_b[0];

  std::vector<fields::FieldSeries> members;
  for (const auto& run : md_out.runs) members.push_back(run.fields);
  const md::ParticleScene& sc = md.spec.scene;
  std::vector<std::vector<std::vector<double>>> member_amplitudes;
  for (const auto& [field, phase] : transport.signals) {
    member_amplitudes.push_back(compare::member_mode_amplitudes(members, field, phase));
    out.signals.push_back(field + ":" +
                          compare::mode_phase_names()[phase == compare::ModePhase::sine ? 0 : 1]);
  }
  std::vector<double> times;
  for (std::size_t s = 0; s < member_amplitudes.front().front().size(); ++s) {
    times.push_back(sc.scaled_time(members.front().snapshots[s].t));
  }

  // The hydro at every grid point; kept: the snapshots from compare.transport_start on that
  // every run has.
  const std::size_t start = static_cast<std::size_t>(transport.start);
  std::vector<std::size_t> kept;
  for (std::size_t s = start; s < times.size(); ++s) kept.push_back(s);
  // hydro[g][i][j][s] at every time (0 where a run has no snapshot)
  std::vector<std::vector<std::vector<std::vector<double>>>> hydro_at(
      transport.signals.size(),
      std::vector<std::vector<std::vector<double>>>(out.grid.factors_a.size()));
  for (std::size_t i = 0; i < out.grid.factors_a.size(); ++i) {
    for (double fb : out.grid.factors_b) {
      HydroScene scene = hydro;
      for (const auto& key : first.factor_keys) {
        set_transport_factor(scene, key, out.grid.factors_a[i]);
      }
      for (const auto& key : second.factor_keys) set_transport_factor(scene, key, fb);
      HydroModel model(scene, md.spec.bins);
      const fields::ModelResult result = model.run();
      if (model.outcome().run.status == hydro::RunStatus::failed) {
        throw std::runtime_error("transport: the hydro at " + first.factor_keys.front() + " = " +
                                 std::to_string(out.grid.factors_a[i]) + ", " +
                                 second.factor_keys.front() + " = " + std::to_string(fb) +
                                 " failed: " + model.outcome().run.stop_reason);
      }
      for (std::size_t g = 0; g < transport.signals.size(); ++g) {
        std::vector<std::size_t> found;
        const std::vector<double> h = hydro_mode_amplitudes(
            *result.fields, transport.signals[g].first, transport.signals[g].second, times, found);
        kept = snapshots_in_both(kept, found);
        std::vector<double> at_times(times.size(), 0.0);
        for (std::size_t k = 0; k < found.size(); ++k) at_times[found[k]] = h[k];
        hydro_at[g][i].push_back(std::move(at_times));
      }
    }
  }
  require_fit_snapshots(kept, start);
  for (std::size_t g = 0; g < transport.signals.size(); ++g) {
    compare::PairSignal signal;
    for (auto& row : hydro_at[g]) {
      signal.hydro.emplace_back();
      for (auto& h : row) signal.hydro.back().push_back(select_snapshots(h, kept));
    }
    for (const auto& m : member_amplitudes[g]) signal.members.push_back(select_snapshots(m, kept));
    out.hydro_and_members.push_back(std::move(signal));
  }
  out.t = select_snapshots(times, kept);

  try {
    out.fit = compare::fit_transport_factor_pair(out.grid, out.hydro_and_members);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("transport: ") + e.what());
  }
  for (const std::string& name : closures) {
    out.first.closures.emplace_back(name, closure_coefficient_value(first, hydro, name));
    out.second.closures.emplace_back(name, closure_coefficient_value(second, hydro, name));
  }
  out.first.factor = out.fit.factor_a, out.first.factor_error = out.fit.error_a;
  out.second.factor = out.fit.factor_b, out.second.factor_error = out.fit.error_b;
  for (auto* c : {&out.first, &out.second}) {
    c->measured = c->factor * c->closure_value;
    c->error = c->factor_error * std::abs(c->closure_value);
  }
  return out;
}

}  // namespace granvv::app
