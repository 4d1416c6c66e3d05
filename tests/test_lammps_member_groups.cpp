// LAMMPS ensemble members on groups of MPI ranks (md.ranks_per_member, scene/md_members.hpp)
// through the real CLI and the real LAMMPS library: under mpirun -np 2 with one rank per member,
// each member runs on a LAMMPS instance of its own rank, as it runs on one rank alone, so the
// outputs equal those of the default run on one rank bit for bit (wall times aside; the resolved
// case differs only in the key itself). On one group of every rank they equal the default's on
// those ranks.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/same_outputs.hpp"

namespace granvv {
namespace {

namespace fs = std::filesystem;

// Two LAMMPS members of 1000 disks, with particle frames and checkpoints at every sample (each
// group writes its member's files while the other runs).
const char* const kTwoLammpsMembers =
    "run md_haff --quiet --no-report --set md.particles=1000 --set md.box_width=125 "
    "--set md.ensemble=2 --set md.t_end=2 --set md.sample_interval=0.5 "
    "--set 'md.output_times=[0, 1, 2]' --set md.snapshot_interval=1 "
    "--set md.checkpoint_interval=1e-6";

// What differs between the two runs by construction: the key itself and the fingerprint of the
// resolved case that holds it.
const std::vector<std::string> kTheKeyAndTheCase = {"ranks_per_member", "case_sha256"};

std::string on_two_ranks(const std::string& args) {
  return "mpirun --allow-run-as-root --oversubscribe -np 2 " + std::string(GRANVV_BINARY) + " " +
         args;
}

TEST(LammpsMemberGroups, OneRankPerMemberOnTwoRanksGivesTheOutputsOfOneRank) {
  const fs::path one = testing::fresh_directory("lammps-groups-1");
  const fs::path two = testing::fresh_directory("lammps-groups-2");
  const auto r1 = testing::run_cli(std::string(kTwoLammpsMembers) + " --out " + one.string());
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  const auto r2 = testing::run_shell(on_two_ranks(
      std::string(kTwoLammpsMembers) + " --set md.ranks_per_member=1 --out " + two.string()));
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  const auto summary = testing::expect_same_outputs(one, two, 2, kTheKeyAndTheCase);
  EXPECT_GT(summary.at("/md/atom_steps").get<double>(), 1e6);
  EXPECT_NE(testing::read_text(two / "run.log").find("2 groups of 1 MPI rank"), std::string::npos);
  fs::remove_all(one);
  fs::remove_all(two);
}

// One group of both ranks (md.ranks_per_member = 2 under -np 2): the members run one after another
// on fresh engines over the group, their checkpoints in blocks, and the outputs are those of the
// default run, whose one engine runs them in turn over every rank.
TEST(LammpsMemberGroups, OneGroupOfEveryRankGivesTheOutputsOfTheDefault) {
  const fs::path one = testing::fresh_directory("lammps-group-default");
  const fs::path two = testing::fresh_directory("lammps-group-of-two");
  const auto r1 =
      testing::run_shell(on_two_ranks(std::string(kTwoLammpsMembers) + " --out " + one.string()));
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  const auto r2 = testing::run_shell(on_two_ranks(
      std::string(kTwoLammpsMembers) + " --set md.ranks_per_member=2 --out " + two.string()));
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  testing::expect_same_outputs(one, two, 2, kTheKeyAndTheCase);
  fs::remove_all(one);
  fs::remove_all(two);
}

// A value that does not divide the ranks, a negative one, and the key given to the engine that
// does not declare it: one line naming the key and its value, exit 2, nothing written.
TEST(LammpsMemberGroups, ABadRanksPerMemberIsRefused) {
  const fs::path out = testing::fresh_directory("lammps-groups-refused");
  fs::remove_all(out);
  const std::string run = "run md_haff --quiet --no-report --out " + out.string() + " --set ";
  const std::string alone = std::string(GRANVV_BINARY) + " " + run;
  struct Refusal {
    std::string command, expected;
  };
  const Refusal refusals[] = {
      {alone + "md.ranks_per_member=2", "md.ranks_per_member = 2: must divide the 1 MPI rank "},
      {alone + "md.ranks_per_member=-1", "md.ranks_per_member = -1"},
      {alone + "md.engine=event_driven --set md.ranks_per_member=1",
       "md.ranks_per_member = 1: a key of md.engine = \"lammps\""},
      {on_two_ranks(run + "md.ranks_per_member=3"),
       "md.ranks_per_member = 3: must divide the 2 MPI ranks "},
  };
  for (const Refusal& r : refusals) {
    SCOPED_TRACE(r.command);
    const auto result = testing::run_shell(r.command);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_NE(result.output.find(r.expected), std::string::npos) << result.output;
    if (r.command.rfind("mpirun", 0) != 0) {  // mpirun adds its own lines about the exit
      EXPECT_EQ(result.output.find('\n'), result.output.size() - 1) << result.output;
    }
    EXPECT_FALSE(fs::exists(out)) << "a refused run made its folder";
  }
}

}  // namespace
}  // namespace granvv
