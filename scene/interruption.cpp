#include "scene/interruption.hpp"

#include <csignal>
#include <cstring>

namespace granvv::app {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_interruption(int sig) {
  if (g_signal != 0) {  // the second request: stop now
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
}

}  // namespace

void catch_interruptions() {
  static const bool installed = [] {
    struct sigaction action;
    std::memset(&action, 0, sizeof action);
    action.sa_handler = on_interruption;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    return true;
  }();
  (void)installed;
}

int interruption_signal() {
  return g_signal;
}

void stop_if_interrupted() {
  if (g_signal == 0) return;
  throw Interrupted(std::string("interrupted by ") + (g_signal == SIGINT ? "SIGINT" : "SIGTERM"));
}

int interrupted_exit_code() {
  return 128 + g_signal;
}

}  // namespace granvv::app
