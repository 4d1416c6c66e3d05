// What a user sees when LAMMPS ends a run on one rank (md_bridge/lammps_session.cpp, granvv's
// MPI_Abort): one line naming LAMMPS and the rank. Disabled in the ordinary suite, because it
// ends the process: tests/CMakeLists.txt runs it under mpirun -np 2 and looks for the line.
#include <gtest/gtest.h>

#include "md_bridge/disk_gas.hpp"
#include "md_bridge/lammps_session.hpp"

namespace granvv::md {
namespace {

TEST(LammpsAbort, DISABLED_AnErrorOnOneRankEndsEveryRankWithOneLine) {
  LammpsSessionOptions options;
  options.comm = MPI_COMM_WORLD;
  LammpsSession session(options);
  create_disk_box(session, 10.0, 10.0);
  // Rank 0 alone reads a dump, and a file it cannot open is LAMMPS's Error::one.
  session.command("read_dump /nonexistent/granvv-no-such-dump 0 x y");
  FAIL() << "LAMMPS went on after a dump it could not open";
}

}  // namespace
}  // namespace granvv::md
