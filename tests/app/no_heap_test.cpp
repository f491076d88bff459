// The controller allocates nothing after init: this binary counts the controller thread's
// heap allocations (operator new and malloc, thread-locally, so the simulated arm's thread
// does not count) while it brings the arm up and runs episodes over the loopback bus.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <new>

#include "tests/app/app_test_util.hpp"

extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void __libc_free(void*);
}

namespace {
thread_local bool t_counting = false;
thread_local long t_allocations = 0;
void note() {
  if (t_counting) ++t_allocations;
}
}  // namespace

extern "C" {
void* malloc(size_t n) {
  note();
  return __libc_malloc(n);
}
void* calloc(size_t n, size_t s) {
  note();
  return __libc_calloc(n, s);
}
void* realloc(void* p, size_t n) {
  note();
  return __libc_realloc(p, n);
}
void free(void* p) {
  __libc_free(p);
}
}
void* operator new(size_t n) {
  note();
  void* p = __libc_malloc(n ? n : 1);
  if (!p) std::abort();
  return p;
}
void* operator new[](size_t n) {
  return operator new(n);
}
void operator delete(void* p) noexcept {
  __libc_free(p);
}
void operator delete[](void* p) noexcept {
  __libc_free(p);
}
void operator delete(void* p, size_t) noexcept {
  __libc_free(p);
}
void operator delete[](void* p, size_t) noexcept {
  __libc_free(p);
}

namespace curio::app::test {
namespace {

TEST(ControllerHeap, NoAllocationAfterInit) {
  const lab::RunSpec spec = mge_efr_spec(sim::Physics::kKinematic, 2, 100, 100);
  ExplorerConfig config;
  ASSERT_EQ(lab::make_explorer_config(spec, &config), Status::kOk);
  auto explorer = std::make_unique<Explorer>();
  ASSERT_EQ(explorer->init(config), Status::kOk);
  auto controller = std::make_unique<Controller>();
  auto wire = hal::LoopbackBus::create();
  auto arm_end = wire->open();
  auto controller_end = wire->open();
  ArmThread arm(arm_end.get(), serve_options(spec));
  ControllerConfig cc;
  cc.want_image = true;  // the ISO-TP path too
  ASSERT_EQ(controller->init(controller_end.get(), explorer.get(), cc), AppStatus::kOk);

  // The counter works: one allocation is seen.
  t_counting = true;
  int* volatile probe = new int(1);
  t_counting = false;
  delete probe;
  ASSERT_EQ(t_allocations, 1);
  t_allocations = 0;

  t_counting = true;
  const AppStatus up = controller->start_arm();
  int episodes = 0;
  while (up == AppStatus::kOk && !explorer->done() && controller->run_episode() == AppStatus::kOk)
    ++episodes;
  t_counting = false;
  arm.stop();
  ASSERT_EQ(up, AppStatus::kOk);
  EXPECT_EQ(episodes, 200);
  EXPECT_EQ(t_allocations, 0) << "heap allocations in the controller's thread after init";
}

}  // namespace
}  // namespace curio::app::test
