// The end-of-run outputs of an online run: the passive baselines (MGE-βVAE with the shipped
// model, and RPE, same seed, σ, bootstrap and physics, run in-process by curio-lab's
// run_exploration), summary.json, curves.csv, interest.csv, latents.csv and three PNGs:
// ratio.png (ratio curves), interest.png (every module slot's interest, retrains marked) and
// latents.png (each latent's |corr| with the four true factors and its KL, round by round:
// how the latents' meaning changed across retrains; evaluation only).
#pragma once
#include <string>

#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_run.hpp"

namespace curio::online {

// Writes the files above into o.out_dir; figure failures (no gnuplot) are warnings on stderr.
void write_final_report(const OnlineOptions& o, const OnlineResult& r);

// What round `round`'s model makes of every scene the run has seen (its scenes.csv): writes
// <out>/codes_round_<round>.csv, "episode,ball_x,ball_y,distractor_x,distractor_y,mu0,..,mu9"
// (μ of the float encoder, as the explorer's outcomes), and returns its path. For analysis
// (evaluation only: the true positions sit beside the codes). Throws on missing files.
std::string export_codes(const OnlineOptions& o, int round);

}  // namespace curio::online
