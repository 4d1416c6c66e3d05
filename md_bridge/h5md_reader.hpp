#pragma once
// H5MD files (de Buyl, Colberg & Höfling, Comp. Phys. Comm. 185, 1546 (2014)): granvv's own
// particles.h5 (h5md_writer.hpp) and other writers'. Read: the one group /particles/<group>
// (or "all" among several), its box (dimension 2, or 3 with the z motion frozen; edges fixed
// or time-dependent but unchanging; offset, if given, as the lower corner), its position and
// velocity elements (value [frames][N][dim], step and time), and its id (fixed [N] or
// time-dependent [frames][N]), if present, by which rows are ordered.
#include <string>

#include "md_bridge/recorded_frames.hpp"

namespace granvv::md {

// One H5MD file's frames (times NaN where the file gives steps only); positions wrapped about
// the box centre (without an offset: about 0, granvv's own box [-L/2, L/2)). With particles
// false the frames keep step and time only (every frame is still read and checked). Throws
// RecordedFileError.
RecordedTrajectory read_h5md(const std::string& path, bool particles);

}  // namespace granvv::md
