#include "models/transport_measurement.hpp"

#include <algorithm>
#include <stdexcept>

#include "compare/mode_amplitudes.hpp"
#include "compare/transport_coefficients.hpp"
#include "models/model.hpp"

namespace granvv::app {

std::vector<std::size_t> snapshots_in_both(const std::vector<std::size_t>& kept,
                                           const std::vector<std::size_t>& found) {
  std::vector<std::size_t> both;
  for (std::size_t s : kept) {
    if (std::find(found.begin(), found.end(), s) != found.end()) both.push_back(s);
  }
  return both;
}

void require_fit_snapshots(const std::vector<std::size_t>& kept, std::size_t start) {
  if (kept.size() < 3 || kept.front() != start) {
    throw std::runtime_error("transport: the hydro and the particles share " +
                             std::to_string(kept.size()) + " snapshot times from snapshot " +
                             std::to_string(start) +
                             " (compare.transport_start) on; the fit needs three from there");
  }
}

std::vector<double> select_snapshots(const std::vector<double>& row,
                                     const std::vector<std::size_t>& kept) {
  std::vector<double> chosen;
  for (std::size_t s : kept) chosen.push_back(row[s]);
  return chosen;
}

std::vector<double> hydro_mode_amplitudes(const fields::FieldSeries& hydro,
                                          const std::string& field, compare::ModePhase phase,
                                          const std::vector<double>& times,
                                          std::vector<std::size_t>& kept) {
  const fields::FieldColumn& column = fields::field_column(field);
  std::vector<double> out;
  std::vector<std::size_t> found;
  for (std::size_t s = 0; s < times.size(); ++s) {
    for (const auto& snap : hydro.snapshots) {
      if (!fields::same_time(snap.t, times[s])) continue;
      out.push_back(compare::field_mode_amplitude(snap.*column.values, field, phase));
      found.push_back(s);
      break;
    }
  }
  kept = std::move(found);
  return out;
}

double closure_coefficient_value(const compare::TransportCoefficient& coefficient,
                                 const HydroScene& hydro, const std::string& closure) {
  HydroScene scene = hydro;
  scene.closure = closure;
  scene.factors = {};
  return coefficient.relative_value(*make_hydro_closure(scene), scene.physics.K, 1, 1);
}

TransportMeasurement measure_transport(const CompareScene::Transport& transport,
                                       const std::vector<std::string>& closures,
                                       const HydroScene& hydro, const MdScene& md,
                                       const MdOutcome& md_out) {
  const compare::TransportCoefficient& coefficient =
      compare::transport_coefficient(transport.coefficient);
  const md::ParticleScene& sc = md.spec.scene;
  TransportMeasurement out;
  out.coefficient = transport.coefficient;
  out.field = transport.field;
  out.phase = compare::mode_phase_names()[transport.phase == compare::ModePhase::sine ? 0 : 1];
  out.closure = hydro.closure;

  std::vector<fields::FieldSeries> members;
  for (const auto& run : md_out.runs) members.push_back(run.fields);
  std::vector<std::vector<double>> amplitudes =
      compare::member_mode_amplitudes(members, transport.field, transport.phase);
  std::vector<double> times;
  for (std::size_t s = 0; s < amplitudes.front().size(); ++s) {
    times.push_back(sc.scaled_time(members.front().snapshots[s].t));
  }

  // The hydro at each factor of the grid, every factor key of the coefficient set to it.
  const std::size_t start = static_cast<std::size_t>(transport.start);
  std::vector<std::size_t> kept;
  for (std::size_t s = start; s < times.size(); ++s) kept.push_back(s);
  for (double factor : transport.factors) {
    HydroScene scene = hydro;
    for (const auto& key : coefficient.factor_keys) set_transport_factor(scene, key, factor);
    HydroModel model(scene, md.spec.bins);
    const fields::ModelResult result = model.run();
    if (model.outcome().run.status == hydro::RunStatus::failed) {
      throw std::runtime_error("transport: the hydro at " + coefficient.factor_keys.front() +
                               " = " + std::to_string(factor) +
                               " failed: " + model.outcome().run.stop_reason);
    }
    std::vector<std::size_t> found;
    std::vector<double> h =
        hydro_mode_amplitudes(*result.fields, transport.field, transport.phase, times, found);
    // Keep the snapshots every run has (a run that stopped early has fewer).
    kept = snapshots_in_both(kept, found);
    std::vector<double> at_times(times.size(), 0.0);
    for (std::size_t i = 0; i < found.size(); ++i) at_times[found[i]] = h[i];
    out.grid.factors.push_back(factor);
    out.grid.amplitudes.push_back(std::move(at_times));
  }
  require_fit_snapshots(kept, start);
  for (auto& row : out.grid.amplitudes) row = select_snapshots(row, kept);
  for (auto& row : amplitudes) row = select_snapshots(row, kept);
  out.t = select_snapshots(times, kept);

  out.fit = compare::fit_transport_factor(out.grid, amplitudes);
  for (const std::string& name : closures) {
    out.closures.emplace_back(name, closure_coefficient_value(coefficient, hydro, name));
  }
  const double value = closure_coefficient_value(coefficient, hydro, hydro.closure);
  out.measured = out.fit.factor * value;
  out.error = out.fit.error * value;
  return out;
}

double injected_coefficient_factor(const std::string& coefficient, const HydroScene& hydro,
                                   const std::string& key, double factor) {
  const compare::TransportCoefficient& c = compare::transport_coefficient(coefficient);
  HydroScene own = hydro;
  own.factors = {};
  HydroScene injected = own;
  set_transport_factor(injected, key, factor);
  const double K = own.physics.K;
  return c.relative_value(*make_hydro_closure(injected), K, 1, 1) /
         c.relative_value(*make_hydro_closure(own), K, 1, 1);
}

}  // namespace granvv::app
