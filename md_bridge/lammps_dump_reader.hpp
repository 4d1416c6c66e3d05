#pragma once
// LAMMPS text dumps (`dump custom ... id x y vx vy`, LAMMPS manual "dump"): one file of one or
// many frames, each
//
//   ITEM: TIME               (optional: dump_modify time yes)
//   ITEM: TIMESTEP           the step
//   ITEM: NUMBER OF ATOMS    N
//   ITEM: BOX BOUNDS pp pp pp    then lo hi per axis (orthogonal boxes only)
//   ITEM: ATOMS <columns>    then N rows
//
// Columns are found by name: id (else the rows in order), the position as x, xu (unwrapped) or
// xs (scaled by the box), likewise y, the velocity vx vy; z/zu/zs and vz, if present, must
// show no motion along z; mass and radius or diameter, if present, must be md.recorded.mass
// and md.recorded.diameter.
#include <string>

#include "md_bridge/recorded_frames.hpp"

namespace granvv::md {

// One dump file's frames (times NaN unless the dump holds ITEM: TIME); positions wrapped about
// the box centre, rows ordered by ID. With particles false the frames keep step and time only
// (every row is still read and checked). Throws RecordedFileError.
RecordedTrajectory read_lammps_dump(const std::string& path, const RecordedOptions& options,
                                    bool particles);

}  // namespace granvv::md
