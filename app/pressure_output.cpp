#include "app/pressure_output.hpp"

#include <H5Cpp.h>

#include <vector>

#include "compare/ensemble_statistics.hpp"
#include "compare/pressure_comparison.hpp"
#include "compare/profile_measures.hpp"
#include "fields/hdf5_datasets.hpp"

namespace granvv::app {
namespace {

// One closure's p(n, T) at the particles' bins (`eos`, [ns x B]) and for the box at n0 and the
// ensemble's T (`box_eos`, [S]).
struct ClosurePressure {
  std::vector<double> eos, box_eos;
};

ClosurePressure closure_pressures(const hydro::Closure& closure, const MdOutcome& out, double n0) {
  ClosurePressure p;
  for (const auto& s : out.fields.snapshots) {
    const auto bins = compare::closure_pressure_md(closure, s.n, s.T, n0);
    p.eos.insert(p.eos.end(), bins.begin(), bins.end());
  }
  const std::vector<double> n_box(out.T.mean.size(), n0);
  p.box_eos = compare::closure_pressure_md(closure, n_box, out.T.mean, n0);
  return p;
}

}  // namespace

void write_pressure_comparison(const std::filesystem::path& file, const HydroScene& hydro,
                               const std::vector<std::string>& closures, const MdScene& md,
                               const MdOutcome& out) {
  const auto& snaps = out.fields.snapshots;
  if (snaps.empty() || snaps.front().P_xx.empty()) return;
  const auto closure = make_hydro_closure(hydro);
  const double n0 = md.spec.scene.number_density();
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group g = h5.createGroup("/compare/pressure");
  h5::write_attribute(g, "closure", closure->name());
  std::vector<double> t, x = snaps.front().x, md_p, md_error, peak_bin;
  for (const auto& s : snaps) {
    t.push_back(s.t);
    const std::vector<double> p = compare::normal_pressure(s.P_xx, s.P_yy);
    const std::vector<double> e = compare::normal_pressure_error(s.P_xx_stderr, s.P_yy_stderr);
    md_p.insert(md_p.end(), p.begin(), p.end());
    md_error.insert(md_error.end(), e.begin(), e.end());
    peak_bin.push_back(static_cast<double>(compare::peak_bin(s.n)));
  }
  const ClosurePressure first = closure_pressures(*closure, out, n0);
  h5::write_vector(g, "t", t);
  h5::write_vector(g, "x", x);
  h5::write_matrix(g, "md", md_p, snaps.size());
  h5::write_matrix(g, "md_error", md_error, snaps.size());
  h5::write_matrix(g, "eos", first.eos, snaps.size());
  h5::write_vector(g, "peak_bin", peak_bin);
  if (closures.size() > 1) {
    H5::Group each = g.createGroup("closures");
    for (const std::string& name : closures) {
      HydroScene scene = hydro;
      scene.closure = name;
      const ClosurePressure p = closure_pressures(*make_hydro_closure(scene), out, n0);
      H5::Group c = each.createGroup(name);
      h5::write_matrix(c, "eos", p.eos, snaps.size());
      h5::write_vector(c, "box_eos", p.box_eos);
    }
  }

  std::vector<std::vector<double>> box;
  for (const auto& run : out.runs) {
    box.push_back(compare::normal_pressure(run.series.pressure_xx, run.series.pressure_yy));
  }
  const compare::EnsembleStatistics mean = compare::ensemble_statistics(box);
  h5::write_vector(g, "box_t", out.runs.front().series.t);
  h5::write_vector(g, "box_md", mean.mean);
  h5::write_vector(g, "box_md_error", mean.standard_error);
  h5::write_vector(g, "box_eos", first.box_eos);
}

}  // namespace granvv::app
