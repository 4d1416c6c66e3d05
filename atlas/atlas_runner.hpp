#pragma once
// The atlas's runs in flight (docs/atlas.md): settings run up to `jobs` at a time (families
// whose runs may go on threads; the others in turn on this thread), each taken from the cache
// when it is there, with a progress line per finished run and the count of runs made now.
#include <filesystem>
#include <mutex>
#include <vector>

#include "models/model_setting.hpp"

namespace granvv::app {

class AtlasRunner {
 public:
  AtlasRunner(const AtlasScene& scene, std::filesystem::path cache, int jobs, bool quiet)
      : scene_(scene), cache_(std::move(cache)), jobs_(jobs), quiet_(quiet) {}

  // The settings' runs, in their order; `estimates` (wall seconds) feed the progress line's ETA.
  // A signal leaves the runs not yet started empty.
  std::vector<AtlasRun> run(const std::vector<AtlasSetting>& settings,
                            const std::vector<double>& estimates);
  AtlasRun run_one(const AtlasSetting& s) { return run({s}, {0.0}).front(); }
  int jobs() const { return jobs_; }
  double spent() const { return spent_; }  // wall seconds of the runs made now
  int made() const { return made_; }       // runs made now (not cached, not refused)
  int done() const { return done_; }

 private:
  const AtlasScene& scene_;
  std::filesystem::path cache_;
  int jobs_;
  bool quiet_;
  std::mutex mutex_;
  int done_ = 0, made_ = 0;
  double spent_ = 0.0;
};

}  // namespace granvv::app
