// The atlas's runs in flight (atlas/atlas_runner.hpp).
#include "atlas/atlas_runner.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <thread>

#include "atlas/atlas_runs.hpp"
#include "models/model_family.hpp"
#include "scene/interruption.hpp"

namespace granvv::app {

std::vector<AtlasRun> AtlasRunner::run(const std::vector<AtlasSetting>& settings,
                                       const std::vector<double>& estimates) {
  std::vector<AtlasRun> runs(settings.size());
  std::atomic<std::size_t> next{0};
  double left = 0.0;
  for (double e : estimates) left += e;
  auto work = [&] {
    for (std::size_t i = next++; i < settings.size(); i = next++) {
      if (interruption_signal()) return;
      runs[i] = run_atlas_setting(scene_, settings[i], cache_);
      std::lock_guard<std::mutex> lock(mutex_);
      if (!runs[i].cache_note.empty())
        std::fprintf(stderr, "atlas: %s\n", runs[i].cache_note.c_str());
      ++done_;
      made_ += !runs[i].cached && runs[i].status != "refused";
      left -= estimates[i];
      spent_ += runs[i].cached ? 0.0 : runs[i].cost.wall_seconds;
      if (!quiet_) {
        std::fprintf(stderr, "atlas: %d runs done, %zu left, ETA %.0f s (%s: %s, %.3g s%s)\n",
                     done_, settings.size() - std::min(settings.size(), next.load()),
                     std::max(0.0, left) / jobs_, describe(settings[i]).c_str(),
                     runs[i].status.c_str(), runs[i].cost.wall_seconds,
                     runs[i].cached ? ", cached" : "");
      }
    }
  };
  // Particle runs call MPI (single-threaded) and are one engine each: on this thread, in turn.
  const bool serial =
      jobs_ == 1 || std::any_of(settings.begin(), settings.end(), [](const AtlasSetting& s) {
        return !model_family(s.model).runs_on_threads();
      });
  if (serial) {
    work();
    return runs;
  }
  std::vector<std::thread> pool;
  for (int j = 0; j < std::min<int>(jobs_, int(settings.size())); ++j) pool.emplace_back(work);
  for (auto& t : pool) t.join();
  return runs;
}

}  // namespace granvv::app
