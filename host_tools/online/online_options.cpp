#include "host_tools/online/online_options.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/explore/config.hpp"

namespace curio::online {

std::vector<int> OnlineOptions::retrain_points() const {
  std::vector<int> points{bootstrap};
  if (retrain_every > 0)
    for (int e = bootstrap + retrain_every; e <= last_retrain && e < bootstrap + episodes;
         e += retrain_every)
      points.push_back(e);
  return points;
}

int OnlineOptions::open_latents_at(double c) const {
  if (!progressive()) return 10;
  // The small slack keeps C exactly at a group's capacity (6 nats = 2 latents × 3) from
  // opening the next group through rounding.
  const int groups = static_cast<int>(std::ceil(c / (group_size * nats_per_latent) - 1e-9));
  return std::min(10, group_size * std::max(1, groups));
}

#define CURIO_ONLINE_FIELDS(X)                                                                \
  X(seed) X(physics) X(sigma) X(bootstrap) X(episodes) X(group_size) X(competence_cap)         \
  X(retrain_every) X(last_retrain) X(first_iterations) X(retrain_iterations) X(beta)          \
  X(capacity_max) X(capacity_iters) X(batch) X(lr) X(out_init_scale) X(unmix) X(eval_images)   \
  X(interest_every) X(progress_every) X(baselines)
#define CURIO_ONLINE_LATER_FIELDS(X) X(nats_per_latent) X(release_scale) X(surprise_fraction) X(surprise_top) \
  X(novelty_fraction) X(novelty_top) X(anchor_weight) X(goal_modules) X(skew_alpha) X(skew_neighbours) X(skew_cap) \
  X(kl_penalty) X(kl_weight) X(decoder) X(goal_scale)

nlohmann::json to_json(const OnlineOptions& o) {
  nlohmann::json j;
#define X(f) j[#f] = o.f;
  CURIO_ONLINE_FIELDS(X)
  CURIO_ONLINE_LATER_FIELDS(X)
#undef X
  return j;
}

OnlineOptions options_from_json(const nlohmann::json& j) {
  OnlineOptions o;
#define X(f) o.f = j.at(#f).get<decltype(o.f)>();
  CURIO_ONLINE_FIELDS(X)
#undef X
  // Fields added later take their defaults (which keep them off) when a run predates them.
#define X(f) o.f = j.value(#f, o.f);
  CURIO_ONLINE_LATER_FIELDS(X)
#undef X
  return o;
}

std::vector<std::string> check(const OnlineOptions& o) {
  std::vector<std::string> p;
  if (o.bootstrap < 1) p.push_back("--bootstrap must be >= 1 (the first training needs images)");
  if (o.episodes < 5 || o.episodes % 5 != 0) p.push_back("--episodes must be a positive multiple of 5");
  if (o.bootstrap + o.episodes > kArchiveCapacity)
    p.push_back("--bootstrap + --episodes exceeds the archive capacity " +
                std::to_string(kArchiveCapacity));
  if (o.retrain_every < 0 || o.retrain_every % 5 != 0)
    p.push_back("--retrain-every must be >= 0 and a multiple of 5 (retrains fall between steps)");
  if (o.group_size < 1 || 10 % o.group_size != 0) p.push_back("--group-size must divide 10");
  if (o.first_iterations < 1 || o.retrain_iterations < 0)
    p.push_back("--first-iterations must be >= 1 and --retrain-iterations >= 0");
  if (o.batch < 1 || o.batch > o.bootstrap) p.push_back("--batch must be in 1..--bootstrap");
  if (!(o.lr > 0) || !(o.beta >= 0) || !(o.capacity_max >= 0) || o.capacity_iters < 1)
    p.push_back("--lr must be > 0, --beta and --capacity-max >= 0, --capacity-iters >= 1");
  if (!(o.sigma >= 0) || !(o.competence_cap > 0)) p.push_back("--sigma >= 0 and --competence-cap > 0");
  if (o.eval_images < 10) p.push_back("--eval-images must be >= 10");
  if (o.interest_every < 1 || o.progress_every < 1)
    p.push_back("--interest-every and --progress-every must be >= 1");
  if (!(o.nats_per_latent >= 0) || !(o.release_scale > 0))
    p.push_back("--nats-per-latent must be >= 0 (0: off) and --release-scale > 0");
  if (!(o.surprise_fraction >= 0 && o.surprise_fraction <= 1) || !(o.surprise_top > 0 && o.surprise_top <= 1))
    p.push_back("--surprise-fraction must be in [0, 1] and --surprise-top in (0, 1]");
  if (!(o.novelty_fraction >= 0 && o.novelty_fraction <= 1) || !(o.novelty_top > 0 && o.novelty_top <= 1))
    p.push_back("--novelty-fraction must be in [0, 1] and --novelty-top in (0, 1]");
  if (!(o.skew_alpha <= 0) || o.skew_neighbours < 1 || !(o.skew_cap >= 1))
    p.push_back("--skew-alpha must be <= 0 (0: off), --skew-neighbours >= 1 and --skew-cap >= 1");
  if (!(o.anchor_weight >= 0)) p.push_back("--anchor-weight must be >= 0 (0: off)");
  if (o.anchor_weight > 0 && !o.progressive())
    p.push_back("--anchor-weight needs progressive latents (--nats-per-latent > 0): it anchors the latents open before a training opens more");
  if (o.goal_modules != "groups" && o.goal_modules != "open-groups" && o.goal_modules != "open-singles")
    p.push_back("--goal-modules must be groups, open-groups or open-singles (not '" + o.goal_modules + "')");
  else if (o.open_goal_modules() && !o.progressive())
    p.push_back("--goal-modules " + o.goal_modules + " needs progressive latents (--nats-per-latent > 0): without them every latent is open");
  if (o.kl_penalty != "abs" && o.kl_penalty != "hinge")
    p.push_back("--kl-penalty must be abs or hinge (not '" + o.kl_penalty + "')");
  if (o.decoder != "spec" && o.decoder != "additive")
    p.push_back("--decoder must be spec or additive (not '" + o.decoder + "')");
  if (!(o.kl_weight >= 0)) p.push_back("--kl-weight must be >= 0 (0: none)");
  if (!(o.goal_scale >= 1e-3 && o.goal_scale <= 1e3)) p.push_back("--goal-scale must be in [0.001, 1000] (1: the prior)");
  if (o.threads < 1) p.push_back("--threads must be >= 1");
  return p;
}

}  // namespace curio::online
