#pragma once
// The particle engine's outputs: the `md` block of summary.json (keys fixed by the
// particle-engine issue, plus the engine's own details; times in MD units sigma sqrt(m/T0)) and the
// /md group of results.h5.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "scene/md_scene.hpp"

namespace granvv::app {

nlohmann::json md_summary(const MdScene& scene, const MdOutcome& outcome);
// The particle part's cost: wall_seconds, the engine's work (by its unit, e.g. atom_steps)
// and that work per second.
nlohmann::json md_cost_summary(const MdOutcome& outcome);

// Adds /md to an existing results.h5: /md/timeseries (run 0's sample times, each member's
// T and energies as [members x samples], the ensemble mean and standard error of T, Haff's
// law with the fitted and both theoretical t0), /md/fields (the FieldSeries: snapshot times x
// bins, ensemble mean and standard error of n, v_x, v_y, T), scene attributes.
void write_md_results(const std::filesystem::path& file, const MdScene& scene,
                      const MdOutcome& outcome);

}  // namespace granvv::app
