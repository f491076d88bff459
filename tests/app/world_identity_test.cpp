// The arm's world has an identity (camera 0x2003: seed, grasp radius, distractor noise,
// renderer version, hash; firmware/protocol/world_identity.hpp), and a run against another
// world than the one it asks for is refused before its first episode, naming the field and
// both values. Seeds are compared whole: 2^32 is not seed 0.
#include <gtest/gtest.h>

#include <filesystem>

#include "firmware/protocol/world_identity.hpp"
#include "hal/host/loopback_bus.hpp"
#include "host_tools/controller/arm_bring_up.hpp"
#include "sim/world_identity.hpp"
#include "tests/app/app_test_util.hpp"

namespace curio::app::test {
namespace {

// Runs `spec` against an arm serving `served` (its own world options); returns the result.
// journal: the run's journal file ("" none), resumed when `resume`.
host::BusRunResult run_against(const lab::RunSpec& spec, const sim::serve::ServeOptions& served,
                               ArchiveCopy* archive, const std::string& journal = "",
                               bool resume = false) {
  auto wire = hal::LoopbackBus::create();
  auto arm_end = wire->open();
  auto controller_end = wire->open();
  ArmThread arm(arm_end.get(), served);
  host::BusRunOptions o;
  o.spec = spec;
  o.controller = fast_fault_config();
  o.journal_path = journal;
  o.resume = resume;
  host::BusRunResult r = host::run_over_bus(controller_end.get(), o, [&](const Explorer& e) {
    *archive = copy_archive(e);
  });
  arm.stop();
  return r;
}

struct Case {
  const char* name;
  void (*change)(sim::serve::ServeOptions*);
  const char* says;  // the message names the field and both values
};

TEST(WorldIdentity, ARunAgainstAnotherWorldIsRefusedNamingTheField) {
  const lab::RunSpec spec = mge_efr_spec(sim::Physics::kKinematic, 0, 20, 10);
  const Case cases[] = {
      {"seed 2^32 (the same low 32 bits)", [](sim::serve::ServeOptions* o) { o->seed = 1ULL << 32; },
       "seed 4294967296 but this run asks for 0"},
      {"grasp radius", [](sim::serve::ServeOptions* o) { o->world.grasp_radius = 0.3; },
       "grasp radius 0.3 but this run asks for 0.1"},
      {"distractor noise", [](sim::serve::ServeOptions* o) { o->world.distractor_noise = 0; },
       "distractor noise 0 but this run asks for 0.1"},
  };
  for (const Case& c : cases) {
    sim::serve::ServeOptions served = serve_options(spec);
    c.change(&served);
    ArchiveCopy archive;
    const host::BusRunResult r = run_against(spec, served, &archive);
    EXPECT_NE(r.run.error.find(c.says), std::string::npos) << c.name << ": " << r.run.error;
    EXPECT_EQ(archive.size, 0) << c.name << ": episodes ran against another world";
    EXPECT_TRUE(r.run.final_ball.empty()) << c.name;
  }
}

TEST(WorldIdentity, TheSameWorldRunsAndIsReportedWhole) {
  lab::RunSpec spec = mge_efr_spec(sim::Physics::kKinematic, (1ULL << 32) + 7, 20, 10);
  spec.world.grasp_radius = 0.25;
  ArchiveCopy archive;
  const host::BusRunResult r = run_against(spec, serve_options(spec), &archive);
  ASSERT_TRUE(r.run.error.empty()) << r.run.error;
  EXPECT_EQ(archive.size, 30);
  ASSERT_TRUE(r.world_published);
  EXPECT_EQ(r.world.seed, (1ULL << 32) + 7);
  EXPECT_EQ(sim::bits_double(r.world.grasp_radius_bits), 0.25);
  EXPECT_EQ(r.world.renderer_version, sim::kRendererVersion);
  const nlohmann::json j = host::world_json(r.world);
  EXPECT_EQ(j.at("seed").get<uint64_t>(), (1ULL << 32) + 7);
  EXPECT_EQ(j.at("grasp_radius").get<double>(), 0.25);
  EXPECT_EQ(j.at("physics"), "kinematic");
  EXPECT_EQ(j.at("hash").get<std::string>().size(), 8u);
}

// A journal keeps its world's hash: resuming it in another world (both the arm and the run
// asking for grasp radius 0.1 where the journal's run had 0.25) is refused, the journal
// unchanged; resumed in its own world it goes on.
TEST(WorldIdentity, AJournalIsResumedOnlyInItsOwnWorld) {
  const auto path = std::filesystem::temp_directory_path() / "curio_world_identity_journal.bin";
  std::filesystem::remove(path);
  lab::RunSpec own = mge_efr_spec(sim::Physics::kKinematic, 3, 20, 10);
  own.world.grasp_radius = 0.25;
  ArchiveCopy archive;
  ASSERT_TRUE(run_against(own, serve_options(own), &archive, path.string()).run.error.empty());
  const auto size = std::filesystem::file_size(path);
  lab::RunSpec other = own;
  other.world.grasp_radius = 0.1;
  const host::BusRunResult r = run_against(other, serve_options(other), &archive, path.string(), true);
  EXPECT_NE(r.run.error.find("world hash"), std::string::npos) << r.run.error;
  EXPECT_EQ(std::filesystem::file_size(path), size);
  const host::BusRunResult same = run_against(own, serve_options(own), &archive, path.string(), true);
  EXPECT_TRUE(same.run.error.empty()) << same.run.error;
  EXPECT_EQ(same.resumed_episodes, 30);
  std::filesystem::remove(path);
}

// Every field moves the hash the journal's identity keeps; the words round-trip.
TEST(WorldIdentity, EveryFieldMovesTheHashAndTheWordsRoundTrip) {
  const protocol::WorldIdentity base =
      sim::world_identity(sim::Physics::kOde, sim::WorldParams{}, 5);
  protocol::WorldIdentity changed[5] = {base, base, base, base, base};
  changed[0].physics = 0;
  changed[1].seed = 5 + (1ULL << 32);
  changed[2].grasp_radius_bits ^= 1;
  changed[3].distractor_noise_bits ^= 1ULL << 40;
  changed[4].renderer_version += 1;
  for (const auto& c : changed) EXPECT_NE(protocol::world_hash(c), protocol::world_hash(base));
  uint32_t words[protocol::kWorldIdentityWords - 1];
  for (uint8_t sub = 1; sub < protocol::kWorldIdentityWords; ++sub)
    words[sub - 1] = protocol::world_identity_word(base, sub);
  const protocol::WorldIdentity back = protocol::world_identity_from_words(words, base.physics);
  EXPECT_EQ(protocol::world_hash(back), protocol::world_identity_word(base, 8));
  EXPECT_EQ(back.seed, base.seed);
  EXPECT_EQ(back.distractor_noise_bits, base.distractor_noise_bits);
}

}  // namespace
}  // namespace curio::app::test
