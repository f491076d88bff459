// Sizes of the board image's components on the target, for toolchain/boards/memory_summary.py:
// each symbol curio_component_<id> is an array as large as one component (sizeof on the
// Cortex-M7, with its ABI's layout). Compiled, never linked: the script reads the sizes with
// `nm -S`, nests the rows by id (explorer__archive is part of explorer) and shows what a
// parent holds beyond its listed parts as its "rest".
#include <cstddef>

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/control_cycle.hpp"
#include "firmware/app/controller.hpp"
#include "firmware/app/episode_capture.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/nn/encoder.hpp"
#include "tests/app/qemu_app/controller_run.hpp"

#define CURIO_COMPONENT(id, bytes)             \
  extern "C" char curio_component_##id[bytes]; \
  char curio_component_##id[bytes]

using namespace curio;

CURIO_COMPONENT(explorer, sizeof(Explorer));
CURIO_COMPONENT(explorer__archive, sizeof(Archive));
CURIO_COMPONENT(explorer__archive__recipes, sizeof(ThetaRecipe) * kArchiveCapacity);
CURIO_COMPONENT(explorer__archive__outcomes, sizeof(float) * kMaxOutcomeDim * kArchiveCapacity);
CURIO_COMPONENT(explorer__archive__pool, sizeof(float) * kThetaDim * kThetaPoolCapacity);
CURIO_COMPONENT(explorer__goal_history, sizeof(GoalHistory));
CURIO_COMPONENT(explorer__frontier, sizeof(FrontierGoals));
CURIO_COMPONENT(controller, sizeof(app::Controller));
CURIO_COMPONENT(controller__capture, sizeof(app::EpisodeCapture));
CURIO_COMPONENT(controller__master, sizeof(app::CanOpenMaster));
CURIO_COMPONENT(controller__cycle, sizeof(app::ControlCycle));
CURIO_COMPONENT(encoder, sizeof(nn::Encoder));
CURIO_COMPONENT(bus, sizeof(test::ImageBus));
CURIO_COMPONENT(fake_arm, sizeof(test::FakeArm));
