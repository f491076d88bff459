// The files of an online run's output folder that make it resumable, and the per-round and
// scene records written beside them:
//   options.json           the run's options (main.cpp writes it; --resume reads it)
//   state.json             rounds done: per round the hash of the scenes it trained on and
//                          its training figures
//   models/round_<r>.pt    the model after training r (weights, Adam state, global iteration)
//   retrain_<r>.json       what round r found (online_run.hpp, RetrainRecord)
//   scenes.csv             every episode's final scene so far (the agent's images, as states)
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/controllability.hpp"
#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_training.hpp"

namespace curio::online {

struct RetrainRecord;

struct RunState {
  std::vector<uint32_t> scene_hashes;   // per round done
  std::vector<TrainingStats> training;  // per round done
};

// An empty state when <dir>/state.json does not exist; throws when it does not parse.
RunState load_state(const std::string& dir);
// Atomic (temporary file, then rename).
void save_state(const std::string& dir, const RunState& state);

std::string round_model_path(const std::string& dir, int round);

// "episode,ball_x,ball_y,distractor_x,distractor_y", floats to 9 digits (curio-lab's format,
// so `curio-train train --scenes` reads it too).
void write_scenes_csv(const std::string& dir, const std::vector<Scene>& scenes);

void write_retrain_json(const std::string& dir, const RetrainRecord& record);

// One module's controllability verdict (lab::classify_modules) as JSON: exploits, mean
// progress, t, relative interest, controllable.
nlohmann::json verdict_json(const lab::ModuleVerdict& v);

}  // namespace curio::online
