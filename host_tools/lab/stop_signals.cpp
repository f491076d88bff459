#include "host_tools/lab/stop_signals.hpp"

#include <csignal>

namespace curio::lab {

namespace {

std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void on_stop_signal(int sig) {
  g_signal = sig;
  g_stop.store(true);
}

}  // namespace

void install_stop_handlers() {
  struct sigaction sa = {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

const std::atomic<bool>* stop_flag() {
  return &g_stop;
}

bool stop_requested() {
  return g_stop.load();
}

const char* stop_signal_name() {
  const int sig = g_signal;
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

int stopped_exit_code() {
  const int sig = g_signal;
  return 128 + (sig > 0 ? sig : SIGINT);
}

}  // namespace curio::lab
