#include "compare/ensemble_fields.hpp"

#include <stdexcept>

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

}  // namespace granvv::compare
