#include "compare/side_by_side.hpp"

#include <algorithm>

#include "compare/model_comparison.hpp"

namespace granvv::compare {

std::vector<std::string> compared_fields(bool transverse) {
  std::vector<std::string> names;
  for (const std::string& name : fields::hydrodynamic_fields()) {
    if (transverse || name != "v_y") names.push_back(name);  // v_y: the transverse flow
  }
  return names;
}

SideBySide judge_side_by_side(const fields::FieldSeries& particles,
                              const fields::FieldSeries& hydro,
                              const std::vector<std::string>& field_names, double sigmas,
                              double agreement_fraction, double signal_to_noise,
                              const VerdictRule& rule) {
  SideBySide out;
  out.pairs = common_snapshots(particles, hydro);
  out.tracks = compare_field_series(particles, hydro, out.pairs, field_names, sigmas);
  for (const auto& [i, j] : out.pairs) out.t.push_back(particles.snapshots[i].t);
  out.window = agreement_window(out.t, out.tracks, agreement_fraction);
  if (!out.window.throughout && out.window.left_at) {
    const auto k = std::find(out.t.begin(), out.t.end(), *out.window.left_at) - out.t.begin();
    const fields::FieldColumn& c = fields::field_column(out.window.first_out);
    const fields::FieldSnapshot& h = hydro.snapshots[out.pairs[k].second];
    const fields::FieldSnapshot& m = particles.snapshots[out.pairs[k].first];
    out.offset_sigmas = box_mean_offset(h.*c.values, m.*c.values, m.*c.standard_error);
  }
  out.kind = classify_disagreement(out.window.throughout, signal_to_noise, out.offset_sigmas, rule);
  return out;
}

}  // namespace granvv::compare
