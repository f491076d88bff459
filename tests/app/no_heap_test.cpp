// The controller allocates nothing after init: this binary counts the controller thread's
// heap allocations (tests/common/allocation_counter.hpp: thread-locally, so the simulated
// arm's thread does not count) while it brings the arm up and runs episodes over the
// loopback bus.
#include <gtest/gtest.h>

#include <memory>

#include "tests/app/app_test_util.hpp"
#include "tests/common/allocation_counter.hpp"

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
  curio::test::start_counting_allocations();
  int* volatile probe = new int(1);
  const long probe_allocations = curio::test::stop_counting_allocations();
  delete probe;
  ASSERT_EQ(probe_allocations, 1);

  curio::test::start_counting_allocations();
  const AppStatus up = controller->start_arm();
  int episodes = 0;
  while (up == AppStatus::kOk && !explorer->done() && controller->run_episode() == AppStatus::kOk)
    ++episodes;
  const long allocations = curio::test::stop_counting_allocations();
  arm.stop();
  ASSERT_EQ(up, AppStatus::kOk);
  EXPECT_EQ(episodes, 200);
  EXPECT_EQ(allocations, 0) << "heap allocations in the controller's thread after init";
}

}  // namespace
}  // namespace curio::app::test
