#include "sim/ode_runtime.hpp"

#include <ode/ode.h>

#include <mutex>

namespace curio::sim {
namespace {

struct ThreadOdeData {
  ThreadOdeData() { dAllocateODEDataForThread(dAllocateMaskAll); }
  ~ThreadOdeData() { dCleanupODEAllDataForThread(); }
};

}  // namespace

void ensure_ode_ready_for_this_thread() {
  static std::once_flag init;
  std::call_once(init, [] { dInitODE2(0); });
  thread_local ThreadOdeData data;
  (void)data;
}

}  // namespace curio::sim
