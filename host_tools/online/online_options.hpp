// The configuration of one online run (curio-online): exploration, retrain schedule, training
// objective, reports. Every field has a default, and the defaults are the best measured
// configuration (docs/online.md, "anc": progressive latents at 3 nats each, novelty steps on 30 %
// of the goal-exploration steps, anchoring at weight 10).
//
// API:
//   OnlineOptions                the fields; only some are command-line options (add_options),
//                                the rest are the recipe, fixed for a run and recorded with it
//   add_options(app, cl)         defines curio-online's command line on a CLI11 app
//   command_line_problem(app, cl) "" or one line naming the option that contradicts another
//   to_json / options_from_json  <out>/options.json: written at the start, read by --resume and
//                                --export-codes (the run's own options govern)
//   removed_option_in(j)         "" or why an options.json cannot run with this version
//   check(o)                     "" or one line naming the first unusable value
//
// Why the recipe fields stay in options.json although the command line cannot set them: a run
// resumes with exactly the configuration that started it, whatever this version's defaults.
// Options of earlier versions that did not help (surprise-weighted and density-skewed batches,
// ICA unmixing, the additive decoder, the hinge capacity term, other goal-module layouts, goals
// beyond the prior) are gone; the commit be4b2e6 still has them. An options.json that sets one of
// them to anything but its old default is refused rather than run differently.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/exploration_options.hpp"
#include "sim/world.hpp"

namespace CLI {
class App;
}

namespace curio::online {

struct OnlineOptions {
  std::string out_dir = "runs_online/seed0";
  bool resume = false;
  // Exploration (SPEC §2: the firmware Explorer, MGE with 2-D latent modules).
  uint64_t seed = 0;
  sim::Physics physics = sim::Physics::kKinematic;
  double sigma = 0.05;
  int bootstrap = 400;
  int episodes = 10000;          // after the bootstrap
  int group_size = 2;            // latents per module (2: five 2-D modules, as MGE-βVAE)
  double competence_cap = 2.0;   // D (the learned goal spaces' default in curio-lab)
  // Goal-exploration strategy (host_tools/experiment/explore_strategies.hpp): "spec" is SPEC
  // §2's loop; "beyond" adds frontier goals and a σ ladder (docs/beyond.md). Written to
  // options.json only when it is not "spec", so a spec run's options stay those of earlier versions.
  std::string explore = "spec";
  // Retrain schedule: the first training at the end of the bootstrap, then one every
  // retrain_every episodes while the episode count is at most last_retrain.
  int retrain_every = 1000;
  int last_retrain = 6400;
  int64_t first_iterations = 6000;
  int64_t retrain_iterations = 2000;
  // Objective and optimiser (docs/training.md, the shipped recipe's, no curriculum):
  // BCE + β·|KL − C|, C rising linearly 0 → capacity_max over the first capacity_iters
  // iterations counted across all trainings of the run; Adam, warm-started.
  double beta = 150.0;
  double capacity_max = 12.0;
  int64_t capacity_iters = 12000;
  int64_t batch = 32;
  double lr = 5e-4;
  double out_init_scale = 0.01;
  // Progressive latents (0: off, all ten latents train from the start). > 0: a training may
  // use only as many latents, in groups of group_size opened in index order, as C at its end
  // needs at nats_per_latent each (at least one group); the rest are held at the prior
  // (VaeImpl::hold_latents) and a group that opens at a retrain starts from fresh read-out
  // weights × release_scale. The goal modules are then the opened groups first. No image,
  // factor or object count is used: the latent count follows the capacity schedule alone.
  double nats_per_latent = 3.0;
  double release_scale = 0.3;
  // Novelty steps (0: off): at the start of each goal-exploration step after the first
  // training, with probability novelty_fraction the step explores around an archived episode
  // drawn uniformly from the novelty_top fraction whose final images the current model
  // reconstructs worst (Explorer::explore_around) instead of around the 1-NN of a goal. An
  // image the model cannot reconstruct shows something its latents do not hold yet (the ball
  // moved, while no latent holds the ball), so the agent repeats and varies what surprised
  // it. The model's own reconstruction error only: no positions, objects or counts.
  double novelty_fraction = 0.3;
  double novelty_top = 0.02;
  // Anchoring (0: off; progressive latents only): a training that opens new latents adds
  // anchor_weight · KL(q(z_l|x) ‖ q_before(z_l|x)) summed over the latents already open, q_before
  // being the encoder before that training, on the same images. The latents that hold what the
  // agent saw so far keep their code, so what is new (the ball, once the agent moves it) goes to
  // the latents that open instead of folding into an old one. The model's own code only.
  double anchor_weight = 10.0;
  // Reports (evaluation only: SPEC §3's uniform held-out scenes and their true factors).
  int eval_images = 2000;
  int interest_every = 50;
  int progress_every = 500;      // episodes between progress lines
  bool baselines = true;         // at the end: passive MGE-βVAE and RPE, same seed, in-process
  // This process only (never in options.json).
  int threads = 1;
  bool quiet = false;
  int stop_after_retrain = -1;   // ≥ 0: stop after that retrain's checkpoint (as if killed)

  bool progressive() const { return nats_per_latent > 0.0; }
  // Latents a training that ends at capacity c may use (10 when not progressive).
  int open_latents_at(double c) const;

  // The episodes (archive sizes) at which the goal space is (re)trained, increasing.
  std::vector<int> retrain_points() const;
};

// What the command line gives: the options, and --export-codes' round (-1: not asked).
struct CommandLine {
  OnlineOptions options;
  int export_round = -1;
  // --explore, the one exploration option curio-online shares with curio-lab and
  // curio-controller (the rest of its explorer is the recipe in options.json); into
  // options.explore by take_exploration_options.
  lab::ExplorationOptions exploration;
};

void add_options(CLI::App& app, CommandLine& cl);
// After parsing: the shared exploration options into cl->options (its strategy).
void take_exploration_options(CommandLine* cl);
// With --resume or --export-codes the run's options.json governs: "" unless the command line
// also sets one of its options (only --out, --threads, --quiet and --stop-after-retrain may go
// with them), else one line naming it.
std::string command_line_problem(const CLI::App& app, const CommandLine& cl);

nlohmann::json to_json(const OnlineOptions& o);
// Fields missing from an older options.json take the value that reproduces that run (a field
// added later: the value that kept its feature off). Throws on a malformed file.
OnlineOptions options_from_json(const nlohmann::json& j);
std::string removed_option_in(const nlohmann::json& j);
std::string check(const OnlineOptions& o);

}  // namespace curio::online
