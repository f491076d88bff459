// Speed of the world on one core: episodes/s of each physics and rendered images/s.
// Run: curio-bench-physics   (figures in the "episodes/s" and "images/s" columns)
#include <benchmark/benchmark.h>

#include <vector>

#include "firmware/explore/prng.hpp"
#include "sim/render.hpp"
#include "sim/world.hpp"

namespace {

using curio::kThetaDim;
using namespace curio::sim;

std::vector<float> random_thetas(int count, uint64_t seed) {
  curio::Prng rng(seed);
  std::vector<float> thetas(static_cast<size_t>(count) * kThetaDim);
  for (float& v : thetas) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  return thetas;
}

void episodes(benchmark::State& state, Physics physics) {
  constexpr int kThetas = 1024;
  const std::vector<float> thetas = random_thetas(kThetas, 1);
  auto world = make_world(physics, {}, 1);
  int i = 0;
  int grasps = 0;
  for (auto _ : state) {
    const SceneState s = world->rollout(&thetas[static_cast<size_t>(i) * kThetaDim]);
    grasps += s.grasped;
    benchmark::DoNotOptimize(s);
    i = (i + 1) % kThetas;
  }
  state.counters["episodes/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["grasp_rate"] =
      static_cast<double>(grasps) / static_cast<double>(state.iterations());
}

void BM_KinematicEpisode(benchmark::State& state) {
  episodes(state, Physics::kKinematic);
}
void BM_OdeEpisode(benchmark::State& state) {
  episodes(state, Physics::kOde);
}

void BM_RenderScene(benchmark::State& state) {
  curio::Prng rng(2);
  constexpr int kScenes = 1024;
  std::vector<Vec2> positions(2 * kScenes);
  for (Vec2& p : positions) p = {rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
  Image image;
  int i = 0;
  for (auto _ : state) {
    render_scene(positions[2 * i], positions[2 * i + 1], &image);
    benchmark::DoNotOptimize(image.data());
    benchmark::ClobberMemory();
    i = (i + 1) % kScenes;
  }
  state.counters["images/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_KinematicEpisode);
BENCHMARK(BM_OdeEpisode);
BENCHMARK(BM_RenderScene);

}  // namespace

BENCHMARK_MAIN();
