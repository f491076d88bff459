// Ctrl-C (SIGINT) and SIGTERM in curio-lab's commands that run a campaign: the campaign stops
// cleanly (finished runs are on disk, runs in flight end before their next episode) and the
// command exits 128 + the signal (130, 143); a second signal kills at once (SA_RESETHAND).
#pragma once
#include <atomic>

namespace curio::lab {

void install_stop_handlers();

// Set by the first SIGINT or SIGTERM (what run_some and the local campaign watch).
const std::atomic<bool>* stop_flag();
bool stop_requested();

// "SIGINT" or "SIGTERM", and the exit status 128 + the signal (SIGINT's when none was seen).
const char* stop_signal_name();
int stopped_exit_code();

}  // namespace curio::lab
