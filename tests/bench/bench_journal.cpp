// curio-bench-journal: what the exploration journal costs per episode. On the host:
// an in-process kinematic episode (propose, roll out, observe) without a journal, and with
// one on a PosixFileStorage file with fdatasync after every record and after every 100, plus
// the append alone; bytes per episode. For the microcontroller: flash for 10,400 episodes on
// the STM32H7 geometry (128 KiB sectors, 32-byte words), checked by journaling them on the
// simulated flash, beside the firmware image in 2 MB. Prints figures; asserts nothing.
//
//   curio-bench-journal [--dir=DIR] [--episodes=N] [benchmark flags]
// DIR: where the journal file goes (default the current folder; fdatasync on tmpfs would cost
// nothing and mean nothing). N: episodes per episode benchmark (default 2000).
#include <benchmark/benchmark.h>
#include <sys/vfs.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "firmware/app/episode_outcome.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/journal/journal.hpp"
#include "hal/host/posix_file_storage.hpp"
#include "hal/sim_flash.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/run.hpp"
#include "sim/world.hpp"

namespace curio::journal::bench {
namespace {

std::string g_dir = ".";
int g_episodes = 2000;

// The paper's run: 100 bootstrap + 10,000 episodes... of which the benchmark runs as many as
// it needs, restarting the run (untimed) when it ends.
struct Episodes {
  Episodes() : explorer(std::make_unique<Explorer>()) {
    spec.algorithm = *lab::find_algorithm("MGE-EFR");
    spec.explorer.seed = 0;
    spec.explorer.n_bootstrap = 100;
    spec.explorer.n_episodes = 10000;
    spec.explorer.competence_cap = static_cast<float>(spec.algorithm.default_competence_clip);
    restart();
  }
  void restart() {
    ExplorerConfig config;
    lab::make_explorer_config(spec, &config);
    explorer->init(config);
    world = sim::make_world(spec.physics, spec.world, lab::world_seed(spec.explorer.seed));
  }
  // One episode; its journal entry in *e.
  void step(EpisodeEntry* e) {
    float theta[kThetaDim];
    explorer->propose(theta);
    e->episode = static_cast<uint32_t>(explorer->episode());
    e->kind = static_cast<uint8_t>(explorer->kind());
    e->module = static_cast<int8_t>(explorer->module());
    e->exploit = explorer->kind() == EpisodeKind::kExploit && explorer->module() >= 0;
    const sim::SceneState s = world->rollout_joint_targets(theta);
    e->outcome_dim = static_cast<uint8_t>(explorer->config().outcome_dim);
    const app::FinalPositions p{s.ball.x, s.ball.y, s.distractor.x, s.distractor.y};
    app::episode_outcome(p, nullptr, nullptr, e->outcome);
    explorer->observe(e->outcome);
    e->progress = explorer->last_progress();
    e->grasped = s.grasped;
    e->ball[0] = static_cast<float>(s.ball.x);
    e->ball[1] = static_cast<float>(s.ball.y);
    e->distractor[0] = static_cast<float>(s.distractor.x);
    e->distractor[1] = static_cast<float>(s.distractor.y);
    e->attempts = 1;
  }
  lab::RunSpec spec;
  std::unique_ptr<Explorer> explorer;
  std::unique_ptr<sim::World> world;
};

RunIdentity identity() {
  RunIdentity id;
  id.outcome_dim = 4;
  id.n_bootstrap = 100;
  id.n_episodes = 10000;
  std::strncpy(id.algorithm_name, "MGE-EFR", kAlgorithmNameBytes - 1);
  return id;
}

// A journal on a file in g_dir, or on a RAM flash (sync_every < 0).
struct Sink {
  explicit Sink(int sync_every) : sync_every_(sync_every) {
    if (sync_every < 0) {
      ram_.assign(2u << 20, 0xFF);
      storage_ = std::make_unique<hal::SimFlash>(ram_.data(), static_cast<uint32_t>(ram_.size()));
    } else {
      path_ = (std::filesystem::path(g_dir) / "curio_bench_journal.bin").string();
      std::filesystem::remove(path_);
      std::string why;
      storage_ = hal::PosixFileStorage::open(path_, &why);
      if (!storage_) std::fprintf(stderr, "bench_journal: %s\n", why.c_str());
    }
    restart();
  }
  ~Sink() {
    storage_.reset();
    if (!path_.empty()) std::filesystem::remove(path_);
  }
  void restart() {
    writer_.create(storage_.get(), identity(),
                   sync_every_ < 0 ? 1 : static_cast<uint32_t>(sync_every_));
    header_bytes_ += writer_.header_stride();
  }
  // Bytes programmed per append, the header blocks left out.
  double record_bytes_per_append() const {
    const double appends = static_cast<double>(writer_.counters().appends);
    return appends > 0
               ? static_cast<double>(storage_->counters().bytes_written - header_bytes_) / appends
               : 0.0;
  }
  bool append(const EpisodeEntry& e) { return writer_.append(e) == JournalStatus::kOk; }
  uint32_t episodes() const { return writer_.episodes(); }
  const hal::StorageCounters& counters() const { return storage_->counters(); }

 private:
  int sync_every_;
  std::vector<uint8_t> ram_;
  std::string path_;
  std::unique_ptr<hal::Storage> storage_;
  JournalWriter writer_;
  uint64_t header_bytes_ = 0;
};

constexpr int kNoJournal = -2;
constexpr int kSimFlash = -1;

// An episode with (or without) journaling it.
void episode(benchmark::State& state, int sync_every) {
  Episodes run;
  std::unique_ptr<Sink> sink;
  if (sync_every != kNoJournal) sink = std::make_unique<Sink>(sync_every);
  EpisodeEntry e;
  for (auto _ : state) {
    if (run.explorer->done()) {
      state.PauseTiming();
      run.restart();
      if (sink) sink->restart();
      state.ResumeTiming();
    }
    run.step(&e);
    if (sink && !sink->append(e)) state.SkipWithError("append failed");
  }
  if (sink) state.counters["bytes/episode"] = sink->record_bytes_per_append();
}

// The append alone, of entries from a real run.
void append_only(benchmark::State& state, int sync_every) {
  Episodes run;
  std::vector<EpisodeEntry> entries(1000);
  for (EpisodeEntry& e : entries) run.step(&e);
  Sink sink(sync_every);
  for (auto _ : state) {
    if (sink.episodes() == entries.size()) {
      state.PauseTiming();
      sink.restart();
      state.ResumeTiming();
    }
    EpisodeEntry e = entries[sink.episodes()];
    if (!sink.append(e)) state.SkipWithError("append failed");
  }
}

void BM_EpisodeNoJournal(benchmark::State& s) {
  episode(s, kNoJournal);
}
void BM_EpisodeFileSyncEvery1(benchmark::State& s) {
  episode(s, 1);
}
void BM_EpisodeFileSyncEvery100(benchmark::State& s) {
  episode(s, 100);
}
void BM_EpisodeSimFlash(benchmark::State& s) {
  episode(s, kSimFlash);
}
void BM_AppendFileSyncEvery1(benchmark::State& s) {
  append_only(s, 1);
}
void BM_AppendFileSyncEvery100(benchmark::State& s) {
  append_only(s, 100);
}
void BM_AppendFileNoSync(benchmark::State& s) {
  append_only(s, 0);
}
void BM_AppendSimFlash(benchmark::State& s) {
  append_only(s, kSimFlash);
}
// The episode benchmarks run exactly g_episodes episodes each, from the same seed, so they
// see the same archive sizes (an episode's cost grows with the archive: nearest neighbours).
void register_episode_benchmarks() {
  for (auto [name, fn] : {std::pair{"BM_EpisodeNoJournal", &BM_EpisodeNoJournal},
                          std::pair{"BM_EpisodeFileSyncEvery1", &BM_EpisodeFileSyncEvery1},
                          std::pair{"BM_EpisodeFileSyncEvery100", &BM_EpisodeFileSyncEvery100},
                          std::pair{"BM_EpisodeSimFlash", &BM_EpisodeSimFlash}})
    benchmark::RegisterBenchmark(name, fn)->Unit(benchmark::kMicrosecond)->Iterations(g_episodes);
}
BENCHMARK(BM_AppendFileSyncEvery1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AppendFileSyncEvery100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AppendFileNoSync)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AppendSimFlash)->Unit(benchmark::kMicrosecond);

// Keeps each benchmark's real and CPU time (µs) for the summary.
class Capture final : public benchmark::ConsoleReporter {
 public:
  struct Times {
    double real_us = -1, cpu_us = -1;
  };
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      // With --benchmark_repetitions the median (reported after the runs) is the figure kept.
      if (r.run_type == Run::RT_Aggregate && r.aggregate_name != "median") continue;
      if (r.error_occurred) continue;
      // "BM_X/iterations:2000" -> "BM_X"
      const std::string name = r.benchmark_name();
      us[name.substr(0, name.find('/'))] = {r.GetAdjustedRealTime(), r.GetAdjustedCPUTime()};
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, Times> us;
};

const char* fs_name(const std::string& dir) {
  struct statfs s {};
  if (statfs(dir.c_str(), &s) != 0) return "unknown";
  switch (static_cast<unsigned long>(s.f_type)) {
    case 0xEF53:
      return "ext2/3/4";
    case 0x01021994:
      return "tmpfs (fdatasync is a no-op: figures do not apply to a disk)";
    case 0x58465342:
      return "xfs";
    case 0x9123683E:
      return "btrfs";
    case 0x794c7630:
      return "overlayfs";
  }
  return "other";
}

void print_summary(const Capture& c) {
  auto get = [&](const char* name) {
    const auto it = c.us.find(name);
    return it == c.us.end() ? Capture::Times{} : it->second;
  };
  const Capture::Times base = get("BM_EpisodeNoJournal");
  std::printf("\n== journal cost per episode on this host (journal file in %s: %s)\n",
              std::filesystem::absolute(g_dir).c_str(), fs_name(g_dir));
  std::printf(
      "  %d in-process kinematic MGE-EFR episodes (seed 0) per episode benchmark; wall-clock"
      " medians (fdatasync waits are wall time), CPU time beside\n",
      g_episodes);
  std::printf("  episode without journal (baseline):  %9.2f us (CPU %.2f us)\n", base.real_us,
              base.cpu_us);
  const struct {
    const char* label;
    const char* episode;
    const char* append;
  } rows[] = {
      {"file, fdatasync every record (default)", "BM_EpisodeFileSyncEvery1",
       "BM_AppendFileSyncEvery1"},
      {"file, fdatasync every 100 records", "BM_EpisodeFileSyncEvery100",
       "BM_AppendFileSyncEvery100"},
      {"simulated STM32H7 flash (RAM)", "BM_EpisodeSimFlash", "BM_AppendSimFlash"},
  };
  for (const auto& r : rows) {
    const Capture::Times ep = get(r.episode), ap = get(r.append);
    std::printf(
        "  episode + journal, %s: %.2f us, +%.2f us, ratio %.3f to the baseline (CPU "
        "%.2f us, ratio %.3f); append alone %.2f us (CPU %.2f us)\n",
        r.label, ep.real_us, ep.real_us - base.real_us,
        base.real_us > 0 ? ep.real_us / base.real_us : 0.0, ep.cpu_us,
        base.cpu_us > 0 ? ep.cpu_us / base.cpu_us : 0.0, ap.real_us, ap.cpu_us);
  }
  std::printf("  append alone, no fdatasync (page cache only): %.2f us\n",
              get("BM_AppendFileNoSync").real_us);
  std::printf("  bytes per episode: %u (one record slot; the file also holds a %u-byte header)\n",
              round_up(record_bytes(4), 32), round_up(static_cast<uint32_t>(kHeaderBytes), 32));
  std::printf(
      "  against a real-arm episode (50 periods x 10 ms = 500,000 us): fdatasync every "
      "record adds %.3f %%\n",
      100.0 * (get("BM_EpisodeFileSyncEvery1").real_us - base.real_us) / 500000.0);

  // Flash sizing for the microcontroller: journal the 10,400 episodes on the simulated part.
  constexpr uint32_t kSector = hal::SimFlash::kStm32h7SectorBytes;
  constexpr uint32_t kFlash = 2u << 20;
  constexpr uint32_t kImage = 304868;  // the Cortex-M7 image's size in bytes
  constexpr uint32_t kEpisodesRun = 10400;
  const uint32_t image_sectors = (kImage + kSector - 1) / kSector;
  std::printf("\n== microcontroller flash (STM32H7: %u KiB sectors, %u-byte flash words, %u KiB)\n",
              kSector / 1024, hal::SimFlash::kStm32h7WordBytes, kFlash / 1024);
  std::printf("  firmware image %u B -> %u sectors (%u B)\n", kImage, image_sectors,
              image_sectors * kSector);
  for (int dim : {4, 10}) {
    const uint32_t rec = round_up(record_bytes(dim), hal::SimFlash::kStm32h7WordBytes);
    const uint32_t header = round_up(static_cast<uint32_t>(kHeaderBytes), 32);
    const uint32_t bytes = header + kEpisodesRun * rec;
    const uint32_t sectors = (bytes + kSector - 1) / kSector;
    // Check on the simulated part: that many sectors hold every record.
    std::vector<uint8_t> ram(sectors * kSector, 0xFF);
    hal::SimFlash flash(ram.data(), sectors * kSector);
    JournalWriter w;
    RunIdentity id = identity();
    id.outcome_dim = static_cast<uint8_t>(dim);
    uint32_t stored = 0;
    if (w.create(&flash, id) == JournalStatus::kOk) {
      EpisodeEntry e;
      e.outcome_dim = static_cast<uint8_t>(dim);
      for (uint32_t i = 0; i < kEpisodesRun; ++i) {
        e.episode = i;
        if (w.append(e) != JournalStatus::kOk) break;
        ++stored;
      }
    }
    const uint32_t total = image_sectors + sectors;
    std::printf(
        "  %-26s record %3u B: %u episodes = %u B -> %u sectors (%u B); journaled on "
        "the simulated part: %u/%u (%llu B programmed); image + journal %u of %u sectors: %s\n",
        dim == 4 ? "engineered features (4-d)" : "learned latents (10-d)", rec, kEpisodesRun, bytes,
        sectors, sectors * kSector, stored, kEpisodesRun,
        static_cast<unsigned long long>(flash.counters().bytes_written), total, kFlash / kSector,
        total <= kFlash / kSector ? "fits" : "does NOT fit");
  }
}

}  // namespace
}  // namespace curio::journal::bench

int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--dir=", 6) == 0)
      curio::journal::bench::g_dir = argv[i] + 6;
    else if (std::strncmp(argv[i], "--episodes=", 11) == 0)
      curio::journal::bench::g_episodes = std::atoi(argv[i] + 11);
    else
      rest.push_back(argv[i]);
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  curio::journal::bench::register_episode_benchmarks();
  curio::journal::bench::Capture capture;
  benchmark::RunSpecifiedBenchmarks(&capture);
  curio::journal::bench::print_summary(capture);
  benchmark::Shutdown();
  return 0;
}
