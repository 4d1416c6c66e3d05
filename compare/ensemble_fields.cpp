#include "compare/ensemble_fields.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "compare/ensemble_error_model.hpp"

namespace granvv::compare {

EnsembleStatistics column_statistics(const std::vector<fields::FieldSeries>& members,
                                     std::size_t snapshot,
                                     std::vector<double> fields::FieldSnapshot::*column) {
  std::vector<std::vector<double>> values;
  for (const auto& m : members) {
    if (snapshot < m.snapshots.size()) values.push_back(m.snapshots[snapshot].*column);
  }
  return ensemble_statistics(values);
}

fields::FieldSeries ensemble_field_series(const std::vector<fields::FieldSeries>& members) {
  if (members.empty()) throw std::invalid_argument("ensemble_field_series: no members");
  const fields::FieldSeries& first = members.front();
  fields::FieldSeries out;
  out.geometry = first.geometry;
  out.bin_edges = first.bin_edges;
  for (std::size_t s = 0; s < first.snapshots.size(); ++s) {
    fields::FieldSnapshot e;
    e.t = first.snapshots[s].t;
    e.label = first.snapshots[s].label;
    e.x = first.snapshots[s].x;
    for (const fields::FieldColumn& c : fields::field_columns()) {
      if (!c.standard_error) continue;  // the positions are not averaged
      EnsembleStatistics st = column_statistics(members, s, c.values);
      e.*c.values = std::move(st.mean);
      e.*c.standard_error = std::move(st.standard_error);
    }
    out.snapshots.push_back(std::move(e));
  }
  return out;
}

const std::vector<std::string>& fields_with_errors() {
  return fields::hydrodynamic_fields();
}

EnsembleMeanFields ensemble_mean_fields(const std::vector<fields::FieldSeries>& members,
                                        const ScaledUnits& units) {
  const fields::FieldSeries ensemble = ensemble_field_series(members);
  EnsembleMeanFields out;
  out.fields.geometry = ensemble.geometry;
  for (double e : ensemble.bin_edges) out.fields.bin_edges.push_back(e / units.length);
  for (std::size_t s = 0; s < ensemble.snapshots.size(); ++s) {
    const fields::FieldSnapshot& mean = ensemble.snapshots[s];
    const fields::FieldSnapshot& first = members.front().snapshots[s];
    fields::FieldSnapshot m;
    m.t = mean.t / units.time;
    m.label = mean.label;
    for (double x : mean.x) m.x.push_back(x / units.length);
    for (std::size_t b = 0; b < mean.n.size(); ++b) {
      m.n.push_back(mean.n[b] / units.density);
      // Poisson for one member's bin count (an ideal gas; S(0) < 1 at finite density, and the
      // calibration corrects the level), in the units of the ensemble.
      m.n_stderr.push_back(mean.count[b] > 0 ? mean.n[b] / std::sqrt(mean.count[b])
                                             : std::numeric_limits<double>::quiet_NaN());
    }
    m.v_x = mean.v_x, m.v_y = mean.v_y, m.T = mean.T, m.count = mean.count;
    m.v_x_stderr = first.v_x_stderr, m.v_y_stderr = first.v_y_stderr, m.T_stderr = first.T_stderr;
    std::vector<std::string> sources;
    for (const auto& name : fields_with_errors()) {
      const fields::FieldColumn& c = fields::field_column(name);
      EnsembleMeanError e =
          ensemble_mean_error(m.*c.standard_error, column_statistics(members, s, c.values));
      sources.push_back(error_source_label(e));
      m.*c.standard_error = std::move(e.error);
    }
    for (double& e : m.n_stderr) e /= units.density;
    out.fields.snapshots.push_back(std::move(m));
    out.error_source.push_back(std::move(sources));
  }
  return out;
}

}  // namespace granvv::compare
