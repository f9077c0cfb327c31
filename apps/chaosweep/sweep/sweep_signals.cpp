#include "apps/chaosweep/sweep/sweep_signals.hpp"

#include <csignal>

namespace chaosweep {

std::atomic<bool> sweep_stop_requested{false};

namespace {

volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  stop_signal = sig;
  sweep_stop_requested.store(true);
}

}  // namespace

void install_sweep_signal_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGXFSZ, SIG_IGN);
}

int stopped_exit_status() { return 128 + (stop_signal ? int(stop_signal) : SIGINT); }

}  // namespace chaosweep
