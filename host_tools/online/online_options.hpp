// The knobs of one online run (curio-online): exploration, retrain schedule, training
// objective, reports. Every field has a default; main.cpp gives each its --help text. The
// options are written to <out>/options.json at the start, and a --resume reads them back (the
// run's own options govern, except threads and stop_after_retrain).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace curio::online {

struct OnlineOptions {
  std::string out_dir = "runs_online/seed0";
  bool resume = false;
  // Exploration (SPEC §2: the firmware Explorer, MGE with 2-D latent modules by default).
  uint64_t seed = 0;
  std::string physics = "kinematic";
  double sigma = 0.05;
  int bootstrap = 400;
  int episodes = 10000;          // after the bootstrap
  int group_size = 2;            // latents per module (2: five 2-D modules, as MGE-βVAE)
  double competence_cap = 2.0;   // D (the learned goal spaces' default in curio-lab)
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
  // The capacity term: "abs" β·|KL − C| (the recipe's: KL is pulled up to C as well as down)
  // or "hinge" β·max(0, KL − C) (C is a ceiling only: the code spends nats only where the
  // reconstruction gains). kl_weight γ adds γ·KL beneath it (a plain β-VAE price per nat;
  // 0: none), so with the hinge a latent carries what is worth more than γ nats of BCE per nat.
  // Why (session 13, docs/online.md): under "abs" the ball's latents, pulled to their share of
  // C while the ball rests, spend it refining the distractor, and that smear of "ball at rest"
  // codes takes a large share of the ball module's goals. Measured in session 14: alone, the
  // hinge does not stop it; with decoder "additive" and γ 20 the smear shrinks to 8 % of goals.
  std::string kl_penalty = "abs";
  double kl_weight = 0.0;
  // The decoder the training reconstructs with: "spec" (SPEC §3's) or "additive" (the same
  // network applied to each open latent group alone, the groups' changes to the empty code's
  // image summed: DecoderImpl::additive_group_size). The encoder, and so the goal space, is
  // SPEC §3's either way. Why: with the shared decoder a group that opens while the ball rests
  // refines the distractor (session 13); an additive group can only draw what it holds alone.
  std::string decoder = "spec";
  double capacity_max = 12.0;
  int64_t capacity_iters = 12000;
  int64_t batch = 32;
  double lr = 5e-4;
  double out_init_scale = 0.01;
  bool unmix = false;            // FastICA on the active latents after each training
  // Progressive latents (0: off, all ten latents train from the start). > 0: a training may
  // use only as many latents, in groups of group_size opened in index order, as C at its end
  // needs at nats_per_latent each (at least one group); the rest are held at the prior
  // (VaeImpl::hold_latents) and a group that opens starts from fresh read-out weights ×
  // release_scale. The modules are then the opened groups. No image, factor or object count
  // is used: the latent count follows the capacity schedule alone.
  double nats_per_latent = 0.0;
  double release_scale = 0.3;
  // Surprise sampling (0: off): at every training after the first, each batch element is drawn
  // with probability surprise_fraction from the surprise_top fraction of images the model
  // reconstructs worst before that training (BCE decoding μ), else uniformly. The rare
  // images that show something new (the ball moved, 2 % of them while no latent holds it)
  // then reach the latents a retrain opens. Images and the model's own error only.
  double surprise_fraction = 0.0;
  double surprise_top = 0.05;
  // Density-skewed batches (0: off; host_tools/online/density_skew.hpp, after Skew-Fit): at
  // every training after the first, an image is drawn with probability ∝ p̂(its code)^skew_alpha
  // (α < 0), p̂ the product over the open modules of a k-NN density (skew_neighbours) of its μ
  // under the model before the training, weights capped at skew_cap × their mean. The code is
  // then learned from data flattened toward uniform over what the agent reached, as a passive
  // β-VAE's uniform scenes are, so prior goals cover the reached scenes (session 15).
  double skew_alpha = 0.0;
  int skew_neighbours = 10;
  double skew_cap = 20.0;
  // Novelty steps (0: off): at the start of each goal-exploration step after the first
  // training, with probability novelty_fraction the step explores around an archived episode
  // drawn uniformly from the novelty_top fraction whose final images the current model
  // reconstructs worst (Explorer::explore_around) instead of around the 1-NN of a goal. An
  // image the model cannot reconstruct shows something its latents do not hold yet (the ball
  // moved, while no latent holds the ball), so the agent repeats and varies what surprised
  // it: the images that would teach a retrain a new latent stop being 2 % of the data.
  // The model's own reconstruction error only: no positions, objects or counts.
  double novelty_fraction = 0.0;
  double novelty_top = 0.02;
  // Anchoring (0: off; progressive latents only): a training that opens new latents adds
  // anchor_weight · KL(q(z_l|x) ‖ q_before(z_l|x)) summed over the latents already open, q_before
  // being the encoder before that training, on the same images. The latents that hold what the
  // agent saw so far keep their code, so what is new (the ball, once the agent moves it) goes to
  // the latents that open instead of folding into an old one. The model's own code only.
  double anchor_weight = 0.0;
  // Goal modules after each training: "groups" (every latent, in groups of group_size by
  // decreasing KL; with progressive latents the opened groups, then the held ones),
  // "open-groups" (progressive latents: only the opened groups; held latents are μ = 0 on
  // every image, so their modules are unreachable and only take ε choices) or "open-singles"
  // (progressive latents: one module per open latent, by decreasing KL). The model's own KL
  // only. Measured in session 13 (docs/online.md): open-singles lowers the ratio, because a
  // 1-D goal space saturates and then shows no learning progress; keep modules 2-D.
  std::string goal_modules = "groups";
  // Goal scale: goals are goal_scale × clip(N(0, I), ±2.5) in each module (1: SPEC §2.3's
  // prior). A β-VAE trained on the agent's own images matches its prior to what the agent has
  // reached (rest scenes and all), so prior goals mostly ask for what was reached already;
  // a scale > 1 puts goal mass beyond it, as a passive model's prior lies beyond the reached
  // part of the arena. The model's code only: no positions or objects.
  double goal_scale = 1.0;
  // Reports (evaluation only: SPEC §3's uniform held-out scenes and their true factors).
  int eval_images = 2000;
  int interest_every = 50;
  int progress_every = 500;      // episodes between progress lines
  bool baselines = true;         // at the end: passive MGE-βVAE and RPE, same seed, in-process
  int threads = 1;
  int stop_after_retrain = -1;   // ≥ 0: stop after that retrain's checkpoint (as if killed)

  bool progressive() const { return nats_per_latent > 0.0; }
  bool open_goal_modules() const { return goal_modules != "groups"; }
  // Latents per goal module when open_goal_modules().
  int goal_module_size() const { return goal_modules == "open-singles" ? 1 : group_size; }
  // Latents a training that ends at capacity c may use (10 when not progressive).
  int open_latents_at(double c) const;

  // The episodes (archive sizes) at which the goal space is (re)trained, increasing.
  std::vector<int> retrain_points() const;
};

nlohmann::json to_json(const OnlineOptions& o);
OnlineOptions options_from_json(const nlohmann::json& j);
// Empty when the options are usable, else one message per problem.
std::vector<std::string> check(const OnlineOptions& o);

}  // namespace curio::online
