#pragma once
// The fingerprint of what a run reads: its resolved case and every file the case names (an
// initial table or snapshot), each file by its SHA-256. A result that is reused (an atlas cache
// entry, a finished sweep point) or continued (a checkpoint) carries the fingerprint of the
// inputs it was made from; where the fingerprint of the inputs now differs, it is not a result
// of them (docs/outputs.md, "Fingerprints of the inputs").
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace granvv::app {

class CaseConfig;

// Lower-case hex SHA-256 of bytes, and of a file's bytes (std::runtime_error if it cannot be read).
std::string text_sha256(std::string_view bytes);
std::string file_sha256(const std::filesystem::path& file);

// The keys of a resolved case that do not change its results (how often to checkpoint or to
// print progress, the consent to a long run).
const std::set<std::string>& keys_outside_the_results();

// {"case": {key: value in TOML syntax}, "case_sha256": ..., "files": [{"path", "sha256"}]}: every
// key of the resolved case but those outside the results and those of the tables named in
// `ignored_tables` (e.g. "atlas", which no single run reads), and the files the case reads, in
// the order the case names them (a file that cannot be read has the sha256 "unreadable").
nlohmann::json input_fingerprint(const CaseConfig& config,
                                 const std::vector<std::string>& ignored_tables = {});

// "" if `recorded` and `now` (both made by input_fingerprint) are the fingerprints of the same
// inputs; else one phrase naming the first thing that changed, e.g.
//   md.restitution = 0.9 then, 0.5 now
//   the file profile.csv changed (sha256 3f2a9c01... then, 8e41d2b7... now)
// A `recorded` that is not a fingerprint gives "no fingerprint of its inputs".
std::string fingerprint_difference(const nlohmann::json& recorded, const nlohmann::json& now);

}  // namespace granvv::app
