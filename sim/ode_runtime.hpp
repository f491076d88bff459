// ODE's process and thread set-up: dInitODE2 once per process and
// ODE's per-thread data in every thread that touches an ODE world.
#pragma once

namespace curio::sim {

// Idempotent and cheap after the first call in a thread; safe from any std::thread.
// The thread's ODE data is released when the thread exits.
void ensure_ode_ready_for_this_thread();

}  // namespace curio::sim
