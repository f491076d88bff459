#include "host_tools/online/online_state.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/online/online_run.hpp"

namespace curio::online {
namespace {

namespace fs = std::filesystem;

nlohmann::json to_json(const TrainingStats& t) {
  return {{"iterations", t.iterations}, {"seconds", t.seconds}, {"recon", t.recon},
          {"kl", t.kl}, {"capacity", t.capacity}, {"open_latents", t.open_latents},
          {"anchored", t.anchored}, {"anchor_kl", t.anchor_kl}};
}

TrainingStats training_from_json(const nlohmann::json& j) {
  TrainingStats t;
  t.iterations = j.at("iterations").get<int64_t>();
  t.seconds = j.at("seconds").get<double>();
  t.recon = j.at("recon").get<double>();
  t.kl = j.at("kl").get<double>();
  t.capacity = j.at("capacity").get<double>();
  t.open_latents = j.value("open_latents", 10);  // older runs: all ten
  t.anchored = j.value("anchored", 0);
  t.anchor_kl = j.value("anchor_kl", 0.0);
  return t;
}

}  // namespace

nlohmann::json verdict_json(const lab::ModuleVerdict& v) {
  return {{"exploits", v.exploits}, {"mean_progress", v.mean_progress}, {"t", v.t},
          {"relative_interest", v.relative_interest}, {"controllable", v.controllable}};
}

RunState load_state(const std::string& dir) {
  RunState s;
  const fs::path p = fs::path(dir) / "state.json";
  if (!fs::exists(p)) return s;
  std::ifstream f(p);
  try {
    const auto j = nlohmann::json::parse(f);
    for (const auto& r : j.at("rounds")) {
      s.scene_hashes.push_back(r.at("scenes_hash").get<uint32_t>());
      s.training.push_back(training_from_json(r.at("training")));
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(p.string() + " does not parse: " + e.what());
  }
  return s;
}

void save_state(const std::string& dir, const RunState& s) {
  nlohmann::json rounds = nlohmann::json::array();
  for (size_t r = 0; r < s.scene_hashes.size(); ++r)
    rounds.push_back({{"round", r}, {"scenes_hash", s.scene_hashes[r]},
                      {"training", to_json(s.training[r])}});
  host::write_file_atomically_or_throw((fs::path(dir) / "state.json").string(),
                                      nlohmann::json{{"rounds", rounds}}.dump(2) + "\n");
}

std::string round_model_path(const std::string& dir, int round) {
  fs::create_directories(fs::path(dir) / "models");
  return (fs::path(dir) / "models" / fmt::format("round_{}.pt", round)).string();
}

void write_scenes_csv(const std::string& dir, const std::vector<Scene>& scenes) {
  std::string text = "episode,ball_x,ball_y,distractor_x,distractor_y\n";
  for (size_t i = 0; i < scenes.size(); ++i)
    text += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g}\n", i, scenes[i][0], scenes[i][1],
                        scenes[i][2], scenes[i][3]);
  host::write_file_atomically_or_throw((fs::path(dir) / "scenes.csv").string(), text);
}

void write_retrain_json(const std::string& dir, const RetrainRecord& r) {
  nlohmann::json j;
  j["round"] = r.round;
  j["episode"] = r.episode;
  j["loaded_from_checkpoint"] = r.loaded;
  j["training"] = to_json(r.training);
  j["kl_per_latent_on_agent_images"] = r.kl;
  j["mu_mean_on_agent_images"] = r.mu_mean;
  j["mu_std_on_agent_images"] = r.mu_std;
  j["kl_order"] = r.kl_order;
  j["modules"] = r.modules;
  j["carried_cp"] = r.carried_cp;
  j["ball_latents"] = r.ball_latents;
  j["distractor_latents"] = r.distractor_latents;
  j["segment_modules"] = r.segment_modules;
  nlohmann::json v = nlohmann::json::array();
  for (const auto& m : r.segment_verdicts) v.push_back(verdict_json(m));
  j["segment_verdicts"] = v;
  j["segment_controllable_latents"] = r.segment_controllable;
  j["scenes_hash"] = r.scenes_hash;
  j["factor_report_heldout_evaluation_only"] = r.factor_report;
  j["factor_report_own_images_evaluation_only"] = r.own_factor_report;
  j["own_images_ball_latents"] = r.own_ball_latents;
  j["own_images_distractor_latents"] = r.own_distractor_latents;
  host::write_file_atomically_or_throw(
      (fs::path(dir) / fmt::format("retrain_{}.json", r.round)).string(), j.dump(2) + "\n");
}

}  // namespace curio::online
