// The fingerprint of a run's inputs (scene/input_fingerprint.hpp): the resolved case and the
// SHA-256 of every file it reads, and the one phrase naming what changed between two.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/case_config.hpp"
#include "scene/input_fingerprint.hpp"

namespace granvv::app {
namespace {

namespace fs = std::filesystem;

const char* kCase =
    "[case]\nname = \"fp\"\n[physics]\nK = 0.01\nq = 0.05\n[initial]\ntype = \"uniform\"\n";

nlohmann::json fingerprint(const std::vector<std::string>& sets) {
  return input_fingerprint(CaseConfig::from_string(kCase, "fp.toml", sets));
}

TEST(InputFingerprint, Sha256OfKnownBytes) {
  // FIPS 180-2, appendix B.1: SHA-256("abc").
  EXPECT_EQ(text_sha256("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(InputFingerprint, NamesTheKeyThatChangedAndIgnoresKeysOutsideTheResults) {
  const auto before = fingerprint({"md.restitution=0.9"});
  EXPECT_EQ(fingerprint_difference(before, fingerprint({"md.restitution=0.9"})), "");
  EXPECT_EQ(fingerprint_difference(before, fingerprint({"md.restitution=0.5"})),
            "md.restitution = 0.9 then, 0.5 now");
  EXPECT_EQ(fingerprint_difference(before,
                                   fingerprint({"md.restitution=0.9", "md.checkpoint_interval=5"})),
            "");
  EXPECT_EQ(before["case_sha256"].get<std::string>().size(), 64u);
}

TEST(InputFingerprint, NamesTheFileThatChanged) {
  const fs::path dir = fs::temp_directory_path() / ("granvv-fp-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path table = dir / "t.csv";
  const auto write = [&](const char* T) {
    std::ofstream(table) << "x, n, v_x, T\n-0.375, 1, 0, 1\n-0.125, 1, 0, 1\n0.125, 1, 0, " << T
                         << "\n0.375, 1, 0, 1\n";
  };
  const std::vector<std::string> sets{"initial.type=\"table\"",
                                      "initial.from=\"" + table.string() + "\""};
  write("1");
  const auto before = fingerprint(sets);
  ASSERT_EQ(before["files"].size(), 1u);
  EXPECT_EQ(before["files"][0]["sha256"], file_sha256(table));
  EXPECT_EQ(fingerprint_difference(before, fingerprint(sets)), "");
  write("2");
  const std::string changed = fingerprint_difference(before, fingerprint(sets));
  EXPECT_EQ(changed.rfind("the file " + table.string() + " changed (sha256 ", 0), 0u) << changed;
  fs::remove_all(dir);
}

TEST(InputFingerprint, HoldsTheRecordedParticlesFilesUnread) {
  // The dumps a recorded-particles case replays are inputs too: a glob's matches, each hashed.
  // The files need not be valid dumps here: the fingerprint hashes their bytes, it does not read
  // frames (the run refuses a bad dump with its own message).
  const fs::path dir = fs::temp_directory_path() / ("granvv-fp-rec-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "dump.1.txt") << "ITEM: TIMESTEP\n0\n";
  std::ofstream(dir / "dump.2.txt") << "ITEM: TIMESTEP\n10\n";
  const std::vector<std::string> sets{
      "md.enabled=true", "md.engine=\"recorded\"",
      "md.recorded.files=[\"" + (dir / "dump.*.txt").string() + "\"]", "md.recorded.timestep=1.0"};
  const auto before = fingerprint(sets);
  ASSERT_EQ(before["files"].size(), 2u) << before.dump();
  EXPECT_EQ(before["files"][1]["sha256"], file_sha256(dir / "dump.2.txt"));
  std::ofstream(dir / "dump.2.txt") << "ITEM: TIMESTEP\n20\n";
  EXPECT_NE(fingerprint_difference(before, fingerprint(sets)).find("dump.2.txt changed"),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(InputFingerprint, ARecordThatIsNotAFingerprintNeverMatches) {
  const auto now = fingerprint({});
  EXPECT_EQ(fingerprint_difference(nullptr, now), "no fingerprint of its inputs");
  EXPECT_EQ(fingerprint_difference({{"case", {}}, {"files", {}}}, now).empty(), false);
  nlohmann::json damaged = now;
  damaged["files"] = {{{"path", 3}}};
  EXPECT_FALSE(fingerprint_difference(damaged, now).empty());
}

}  // namespace
}  // namespace granvv::app
