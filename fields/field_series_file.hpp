#pragma once
// The one HDF5 layout of a FieldSeries (docs/outputs.md, "FieldSeries groups"), written and read
// here for every group that holds one (/hydro/fields, /md/fields):
//   attribute geometry  "cells" or "bins"
//   t [ns], label [ns]  snapshot times and labels
//   bin_edges [B + 1]   bins only
//   x, n, v_x, T [ns x N], and where the model has them v_y, the *_stderr of each field,
//   count and count_stderr [ns x N].
#include <H5Cpp.h>

#include "fields/field_series.hpp"

namespace granvv::fields {

// Throws std::invalid_argument if the snapshots disagree in length or in which columns they
// carry (a column is written when every snapshot has it).
void write_field_series(H5::Group& group, const FieldSeries& series);

// Throws std::runtime_error on a group that is not in this layout.
FieldSeries read_field_series(const H5::Group& group);

}  // namespace granvv::fields
