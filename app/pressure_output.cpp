#include "app/pressure_output.hpp"

#include <H5Cpp.h>

#include <cmath>
#include <limits>
#include <vector>

#include "compare/ensemble_statistics.hpp"
#include "fields/hdf5_datasets.hpp"

namespace granvv::app {
namespace {

// The closure's pressure in MD units at MD densities and temperatures (scaled n = n_md / n0,
// T unchanged, p_md = p n0 with T0 = 1); NaN where n or T is not finite.
std::vector<double> closure_pressure(const hydro::Closure& closure, const std::vector<double>& n,
                                     const std::vector<double>& T, double n0) {
  std::vector<double> out(n.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<double> ns, Ts;
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (std::isfinite(n[i]) && std::isfinite(T[i]) && n[i] > 0 && T[i] > 0) {
      ns.push_back(n[i] / n0), Ts.push_back(T[i]), at.push_back(i);
    }
  }
  hydro::CellCoefficients c;
  closure.cell_coefficients(ns, Ts, c);
  for (std::size_t k = 0; k < at.size(); ++k) out[at[k]] = c.pressure[k] * n0;
  return out;
}

// One closure's p(n, T) at the particles' bins (`eos`, [ns x B]) and for the box at n0 and the
// ensemble's T (`box_eos`, [S]).
struct ClosurePressure {
  std::vector<double> eos, box_eos;
};

ClosurePressure closure_pressures(const hydro::Closure& closure, const MdOutcome& out, double n0) {
  ClosurePressure p;
  for (const auto& s : out.fields.snapshots) {
    const auto bins = closure_pressure(closure, s.n, s.T, n0);
    p.eos.insert(p.eos.end(), bins.begin(), bins.end());
  }
  const std::vector<double> n_box(out.T.mean.size(), n0);
  p.box_eos = closure_pressure(closure, n_box, out.T.mean, n0);
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
    for (std::size_t b = 0; b < s.P_xx.size(); ++b) {
      md_p.push_back(0.5 * (s.P_xx[b] + s.P_yy[b]));
      md_error.push_back(0.5 * std::hypot(s.P_xx_stderr[b], s.P_yy_stderr[b]));
    }
    std::size_t peak = 0;
    for (std::size_t b = 1; b < s.n.size(); ++b)
      if (s.n[b] > s.n[peak]) peak = b;
    peak_bin.push_back(static_cast<double>(peak));
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
    std::vector<double> p;
    for (std::size_t i = 0; i < run.series.pressure_xx.size(); ++i)
      p.push_back(0.5 * (run.series.pressure_xx[i] + run.series.pressure_yy[i]));
    box.push_back(std::move(p));
  }
  const compare::EnsembleStatistics mean = compare::ensemble_statistics(box);
  h5::write_vector(g, "box_t", out.runs.front().series.t);
  h5::write_vector(g, "box_md", mean.mean);
  h5::write_vector(g, "box_md_error", mean.standard_error);
  h5::write_vector(g, "box_eos", first.box_eos);
}

}  // namespace granvv::app
