#pragma once
// The hydro's snapshots as a FieldSeries on its own Lagrangian cells (fields/field_series.hpp):
// at each cell centre the cell density m_i / w_i and temperature, and the mean of the cell's
// two node velocities. No standard errors: the hydro is deterministic; its numerical error is
// measured by the convergence study (hydro/convergence_study.hpp).
#include <vector>

#include "fields/field_series.hpp"
#include "hydro/driver.hpp"

namespace granvv::hydro {

fields::FieldSeries cell_field_series(const std::vector<Snapshot>& snapshots);

}  // namespace granvv::hydro
