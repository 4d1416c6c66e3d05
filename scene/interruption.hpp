#pragma once
// SIGINT and SIGTERM ask a run to stop at its next safe point (a hydro step, a particle sample)
// instead of killing it in the middle of a write (docs/outputs.md, "The output protocol"). A
// second signal of either kind ends the process at once.
#include <stdexcept>
#include <string>

namespace granvv::app {

// Thrown at a safe point after a signal: the run ends with status "interrupted".
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Installs the handlers of SIGINT and SIGTERM (once; later calls do nothing).
void catch_interruptions();
// The signal received (SIGINT or SIGTERM), or 0.
int interruption_signal();
// Throws Interrupted if a signal was received.
void stop_if_interrupted();
// The exit code of a run stopped by a signal: 128 + its number, as a shell reports it.
int interrupted_exit_code();

}  // namespace granvv::app
