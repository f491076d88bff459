#include "host_tools/experiment/simulated_run.hpp"

#include <chrono>
#include <ctime>
#include <memory>

#include "firmware/app/episode_outcome.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/nn/encoder.hpp"
#include "host_tools/experiment/run_explorer.hpp"
#include "host_tools/experiment/run_recorder.hpp"
#include "sim/camera.hpp"

namespace curio::lab {

namespace {

// Turns the final state into the explorer's outcome, by the controller's own step
// (app::episode_outcome). Learned goal spaces see only the camera frame, through the same
// int8 encoder the controller runs.
bool outcome_of(const AlgorithmSpec& algo, const sim::SceneState& s, nn::Encoder* encoder,
                sim::Image* image, sim::CameraFrame* frame, float* outcome) {
  const bool learned = algo.outcome == OutcomeSource::kLatents;
  if (learned) {
    sim::render_scene(s.ball, s.distractor, image);
    sim::to_camera_frame(*image, frame);
  }
  const app::FinalPositions final_positions{.ball_x = s.ball.x,
                                            .ball_y = s.ball.y,
                                            .distractor_x = s.distractor.x,
                                            .distractor_y = s.distractor.y};
  return app::episode_outcome(final_positions, learned ? encoder : nullptr, frame->data(), outcome);
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace

RunResult run_exploration(const RunSpec& spec, std::atomic<int64_t>* episodes_done,
                          const std::function<void(const Explorer&)>& on_finish,
                          const RunHooks& hooks) {
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_seconds();
  RunResult r;
  r.spec = spec;

  RunExplorer x;
  if (!make_run_explorer(spec, &x, &r.error)) return r;
  const std::unique_ptr<Explorer>& explorer = x.explorer;
  const ExplorerConfig& config = x.config;
  auto world = sim::make_world(spec.physics, spec.world, world_seed(spec.explorer.seed));
  // Image buffers, allocated once.
  auto image = std::make_unique<sim::Image>();
  auto frame = std::make_unique<sim::CameraFrame>();
  RunRecorder recorder(*explorer, x.rep, &r);

  float theta[kThetaDim];
  float outcome[kMaxOutcomeDim] = {};
  const int total = explorer->total_episodes();
  if (hooks.resume) {
    const auto replayed = [&](const journal::EpisodeEntry& e) {
      recorder.record_episode(e.exploit, e.module, e.progress, e.ball[0], e.ball[1], e.grasped);
      r.final_distractor.push_back({e.distractor[0], e.distractor[1]});
    };
    if (!hooks.resume(config, *explorer, replayed, &r.error)) return r;
    // The world's randomness is a function of (seed, episode): the next episode is the one
    // an uninterrupted run has.
    if (explorer->episode() > 0)
      world->reset_to_episode(static_cast<uint64_t>(explorer->episode()));
    if (episodes_done) episodes_done->fetch_add(explorer->episode());
  }
  int reported = explorer->episode();  // episodes counted into *episodes_done
  while (!explorer->done()) {
    if (hooks.stop && hooks.stop->load(std::memory_order_relaxed)) {
      r.error = kStopped;
      return r;
    }
    if (const Status s = explorer->propose(theta); s != Status::kOk) {
      r.error = std::string("propose failed: ") + to_string(s);
      return r;
    }
    const bool exploit = explorer->kind() == EpisodeKind::kExploit && explorer->module() >= 0;
    // The arm moves as it does over the bus: joint targets quantized to counts (parity).
    const sim::SceneState final_state = world->rollout_joint_targets(theta);
    if (!outcome_of(spec.algorithm, final_state, x.encoder.get(), image.get(), frame.get(),
                    outcome)) {
      r.error = "encoder failed on episode " + std::to_string(explorer->episode());
      return r;
    }
    const int episode = explorer->episode();
    const EpisodeKind kind = explorer->kind();
    const int module = explorer->module();
    if (const Status s = explorer->observe(outcome); s != Status::kOk) {
      r.error = std::string("observe failed: ") + to_string(s);
      return r;
    }
    if (hooks.on_episode) {
      journal::EpisodeEntry e;
      e.episode = static_cast<uint32_t>(episode);
      e.kind = static_cast<uint8_t>(kind);
      e.module = static_cast<int8_t>(module);
      e.exploit = exploit;
      e.grasped = final_state.grasped;
      e.attempts = 1;
      e.outcome_dim = static_cast<uint8_t>(config.outcome_dim);
      e.ball[0] = static_cast<float>(final_state.ball.x);
      e.ball[1] = static_cast<float>(final_state.ball.y);
      e.distractor[0] = static_cast<float>(final_state.distractor.x);
      e.distractor[1] = static_cast<float>(final_state.distractor.y);
      e.progress = explorer->last_progress();
      for (int i = 0; i < config.outcome_dim; ++i) e.outcome[i] = outcome[i];
      if (!hooks.on_episode(e, &r.error)) return r;
    }
    // The metric sees the float position a controller gets over the bus (ground truth).
    recorder.record_episode(exploit, explorer->module(), explorer->last_progress(),
                            static_cast<float>(final_state.ball.x),
                            static_cast<float>(final_state.ball.y), final_state.grasped);
    r.final_distractor.push_back({static_cast<float>(final_state.distractor.x),
                                  static_cast<float>(final_state.distractor.y)});
    const int n = explorer->episode();
    if (episodes_done && (n % 100 == 0 || n == total)) {
      episodes_done->fetch_add(n - reported);
      reported = n;
    }
  }
  recorder.finish();
  if (on_finish) on_finish(*explorer);
  r.cpu_seconds = thread_cpu_seconds() - cpu0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace curio::lab
