#include "host_tools/lab/slurm_jobs.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "host_tools/lab/campaign_task.hpp"

namespace curio::lab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The shortest decimal that parses back to exactly `v` (std::stod in the task).
std::string exact_number(double v) {
  char buf[40];
  if (v == std::trunc(v) && std::fabs(v) < 1e15) {  // 1000, not 1e+03
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::stod(buf) == v) break;
  }
  return buf;
}

template <class Int>  // seeds (uint64_t) or array indices (int)
std::string seeds_text(const std::vector<Int>& seeds) {
  std::string out;
  for (size_t i = 0; i < seeds.size();) {
    size_t j = i;
    while (j + 1 < seeds.size() && seeds[j + 1] == seeds[j] + 1) ++j;
    if (!out.empty()) out += ',';
    out += std::to_string(seeds[i]);
    if (j > i) out.append("-").append(std::to_string(seeds[j]));
    i = j + 1;
  }
  return out;
}

std::string joined(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (const auto& s : items) {
    if (!out.empty()) out += sep;
    out += s;
  }
  return out;
}

bool write_file(const fs::path& path, const std::string& text, bool executable,
                std::string* error) {
  if (!host::write_file_atomically(path.string(), text, error)) return false;
  if (executable) {
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add, ec);
  }
  return true;
}

// The #SBATCH header shared by every script.
std::string header(const std::string& comment, const SlurmResources& r, const std::string& time,
                   const std::string& log) {
  std::ostringstream s;
  s << "#!/bin/bash\n" << comment;
  s << "#SBATCH --job-name=" << r.job_name << "\n#SBATCH --cpus-per-task=" << r.cpus
    << "\n#SBATCH --time=" << time << "\n#SBATCH --output=" << log << '\n';
  if (!r.partition.empty()) s << "#SBATCH --partition=" << r.partition << '\n';
  for (const auto& e : r.extra) s << "#SBATCH " << e << '\n';
  return s.str();
}

bool prepare_dirs(const std::string& out_dir, fs::path* slurm_dir, std::string* error) {
  if (out_dir.find_first_of(" \t\n'\"") != std::string::npos) {
    *error = "--out '" + out_dir + "': #SBATCH lines cannot carry whitespace or quotes in paths";
    return false;
  }
  *slurm_dir = fs::path(out_dir) / "slurm";
  std::error_code ec;
  fs::create_directories(*slurm_dir / "logs", ec);
  if (ec) *error = "cannot create " + (*slurm_dir / "logs").string() + ": " + ec.message();
  return !ec;
}

}  // namespace

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<std::string> campaign_run_options(const CampaignConfig& c) {
  std::vector<std::string> sigmas;
  for (double s : c.sigmas) sigmas.push_back(exact_number(s));
  std::vector<std::string> o = {
      "--algos",    joined(c.algorithms, ","), "--seeds",   seeds_text(c.seeds),
      "--noise",    joined(sigmas, ","),       "--physics", sim::physics_name(c.physics),
      "--episodes", std::to_string(c.episodes)};
  if (c.bootstrap >= 0) o.insert(o.end(), {"--bootstrap", std::to_string(c.bootstrap)});
  if (c.competence_clip > 0)
    o.insert(o.end(), {"--competence-clip", exact_number(c.competence_clip)});
  o.insert(o.end(), {"--competence", to_string(c.competence_measure), "--window",
                     exact_number(c.window), "--epsilon", exact_number(c.epsilon), "--grasp-radius",
                     exact_number(c.world.grasp_radius), "--distractor-noise",
                     exact_number(c.world.distractor_noise), "--tie-rule",
                     c.tie_rule == TieRule::kEarliest ? "earliest" : "latest"});
  if (c.explore != "spec") o.insert(o.end(), {"--explore", c.explore});
  return o;
}

std::string array_spec(const std::vector<int>& indices) {
  return seeds_text(indices);
}

std::string slurm_time(double seconds) {
  const long minutes = std::max(1L, static_cast<long>(std::ceil(seconds / 60.0)));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:00", minutes / 60, minutes % 60);
  return buf;
}

std::vector<std::pair<std::string, double>> cpu_seconds_per_episode(const CampaignConfig& config,
                                                                    int episodes) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& spec : expand_runs(config)) {
    const auto seen = [&](const auto& p) { return p.first == spec.algorithm.name; };
    if (std::any_of(out.begin(), out.end(), seen)) continue;
    RunSpec probe = spec;
    probe.explorer.n_episodes = std::max(5, std::min(spec.explorer.n_episodes, episodes) / 5 * 5);
    const RunResult r = run_exploration(probe);
    out.push_back({spec.algorithm.name,
                   r.cpu_seconds / double(probe.explorer.n_bootstrap + probe.explorer.n_episodes)});
  }
  return out;
}

double estimate_task_seconds(const CampaignConfig& config, int runs_per_task, int cpus,
                             std::string* basis) {
  // Short probes: the nearest-neighbour search grows with the archive, so they underrate long
  // kinematic runs a little (ODE and learned goal spaces spend their time elsewhere); × 3.
  const int probe = config.physics == sim::Physics::kOde ? 300 : 1000;
  double slowest = 0.0;
  std::string slowest_name;
  for (const auto& [name, per_episode] : cpu_seconds_per_episode(config, probe)) {
    const double run =
        per_episode *
        (config.episodes +
         (config.bootstrap >= 0 ? config.bootstrap : find_algorithm(name)->default_bootstrap));
    if (run >= slowest) slowest = run, slowest_name = name;
  }
  const int waves = (runs_per_task + cpus - 1) / std::max(cpus, 1);
  const double seconds = 3.0 * waves * slowest + 300.0;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "estimated here: %s %.3g s per run (CPU, %s physics) × %d run(s) per core × 3 + "
                "5 min",
                slowest_name.c_str(), slowest, sim::physics_name(config.physics), waves);
  *basis = buf;
  return seconds;
}

bool write_campaign_job(const CampaignJobRequest& q, SlurmJobFiles* files, std::string* error) {
  fs::path dir;
  if (!prepare_dirs(q.out_dir, &dir, error)) return false;
  const auto specs = expand_runs(q.config);
  const int tasks = tasks_for_chunk(specs.size(), q.chunk);
  const json identity = {{"campaign", campaign_to_json(q.config)},
                         {"tasks", tasks},
                         {"runs_in_campaign", specs.size()}};
  const fs::path identity_path = dir / "campaign.json";
  if (fs::exists(identity_path)) {
    std::ifstream f(identity_path);
    const json old = json::parse(f, nullptr, false);
    if (old.is_discarded() || old != identity) {
      std::string why;
      if (!old.is_discarded()) {
        for (const auto& d :
             campaign_differences(old.value("campaign", json::object()), identity["campaign"]))
          why += "\n  " + d;
        if (old.value("tasks", -1) != tasks)
          why += "\n  tasks: " + old.value("tasks", json()).dump() + " vs " +
                 std::to_string(tasks) + " (use the same --chunk)";
      }
      *error = q.out_dir + " holds another campaign or split (" + identity_path.string() +
               " vs now):" + (why.empty() ? " unreadable" : why) + "\nuse another --out";
      return false;
    }
  } else if (!write_file(identity_path, identity.dump(2) + "\n", false, error)) {
    return false;
  }

  files->dir = dir.string();
  files->tasks = tasks;
  files->array.clear();
  const fs::path tasks_dir = fs::path(q.out_dir) / "tasks";
  for (int t = 0; t < tasks; ++t) {
    CampaignConfig c = q.config;
    if (!runs_to_do(c, (tasks_dir / ("task-" + std::to_string(t))).string(), t, tasks).empty())
      files->array.push_back(t);
  }
  const int runs_per_task = static_cast<int>((specs.size() + tasks - 1) / tasks);
  files->time = q.resources.time;
  files->time_basis = "--time";
  if (files->time.empty()) {
    files->time = slurm_time(
        estimate_task_seconds(q.config, runs_per_task, q.resources.cpus, &files->time_basis));
  }
  std::string options;
  for (const auto& o : q.run_options) options.append(" ").append(shell_quote(o));
  const std::string bin = shell_quote(q.binary);

  files->array_script.clear();
  if (!files->array.empty()) {
    std::ostringstream s;
    s << header("# curio-lab campaign, " + std::to_string(specs.size()) + " runs in " +
                    std::to_string(tasks) + " tasks of at most " + std::to_string(runs_per_task) +
                    " (task I: the runs i with i mod " + std::to_string(tasks) +
                    " = I).\n# Written by `curio-lab slurm`; time: " + files->time_basis + ".\n",
                q.resources, files->time, (dir / "logs" / "task-%a.out").string())
      << "#SBATCH --array=" << array_spec(files->array) << "\n"
      << "set -euo pipefail\n"
      << "task=${SLURM_ARRAY_TASK_ID:?submit with sbatch}\n"
      << "exec " << bin << " run" << options << " --threads " << q.resources.cpus
      << " --task \"$task\" --tasks " << tasks << " --out "
      << shell_quote((tasks_dir / "task-").string()) << "\"$task\"\n";
    files->array_script = (dir / "array.sbatch").string();
    if (!write_file(files->array_script, s.str(), false, error)) return false;
  }
  SlurmResources merge_resources = q.resources;
  merge_resources.cpus = 1;
  merge_resources.job_name = q.resources.job_name + "-merge";
  std::ostringstream m;
  m << header("# Merges the task folders into the campaign's summary, CSVs and plots.\n",
              merge_resources, "0:30:00", (dir / "logs" / "merge.out").string())
    << "set -euo pipefail\n"
    << "exec " << bin << " merge " << shell_quote(tasks_dir.string()) << " --out "
    << shell_quote(q.out_dir) << "\n";
  files->merge_script = (dir / "merge.sbatch").string();
  if (!write_file(files->merge_script, m.str(), false, error)) return false;

  std::ostringstream sub;
  sub << "#!/bin/bash\n# Submits the array (the tasks still to do when it was written) and the "
         "merge after it.\nset -euo pipefail\n";
  if (files->array.empty()) {
    sub << "merge=$(sbatch --parsable " << shell_quote(files->merge_script) << ")\n"
        << "echo \"merge job ${merge%%;*} (every task was complete)\"\n";
  } else {
    sub << "array=$(sbatch --parsable " << shell_quote(files->array_script) << ")\n"
        << "array=${array%%;*}\n"
        << "merge=$(sbatch --parsable --dependency=afterok:$array --kill-on-invalid-dep=yes "
        << shell_quote(files->merge_script) << ")\n"
        << "echo \"array job $array, merge job ${merge%%;*}\"\n";
  }
  files->submit_script = (dir / "submit.sh").string();
  return write_file(files->submit_script, sub.str(), true, error);
}

bool write_train_job(const TrainJobRequest& q, SlurmJobFiles* files, std::string* error) {
  fs::path dir;
  if (!prepare_dirs(q.out_dir, &dir, error)) return false;
  files->dir = dir.string();
  files->tasks = static_cast<int>(q.seeds.size());
  files->array.clear();
  for (int seed : q.seeds)
    if (!fs::exists(fs::path(q.out_dir) / ("seed-" + std::to_string(seed)) / q.done_file))
      files->array.push_back(seed);
  files->time = q.resources.time;
  files->time_basis = "--time";
  files->merge_script.clear();
  files->array_script.clear();
  std::ostringstream sub;
  sub << "#!/bin/bash\n# Submits the seeds not finished when it was written.\nset -euo pipefail\n";
  if (!files->array.empty()) {
    std::ostringstream s;
    s << header("# curio-train seeds: " + shell_quote(q.script) + " OUT/seed-S S, one array task " +
                    "per seed S (the array index).\n# Written by `curio-lab slurm-train`; the "
                    "script resumes a killed seed from its checkpoints.\n",
                q.resources, files->time, (dir / "logs" / "seed-%a.out").string())
      << "#SBATCH --array=" << array_spec(files->array) << "\n"
      << "set -euo pipefail\n"
      << "seed=${SLURM_ARRAY_TASK_ID:?submit with sbatch}\n"
      << "export THREADS=" << q.resources.cpus << "\n";
    if (!q.trainer.empty()) s << "export CURIO_TRAIN=" << shell_quote(q.trainer) << "\n";
    s << "exec bash " << shell_quote(q.script) << " "
      << shell_quote((fs::path(q.out_dir) / "seed-").string()) << "\"$seed\" \"$seed\"\n";
    files->array_script = (dir / "train.sbatch").string();
    if (!write_file(files->array_script, s.str(), false, error)) return false;
    sub << "array=$(sbatch --parsable " << shell_quote(files->array_script) << ")\n"
        << "echo \"array job ${array%%;*}\"\n";
  } else {
    sub << "echo 'every seed is finished'\n";
  }
  files->submit_script = (dir / "submit.sh").string();
  return write_file(files->submit_script, sub.str(), true, error);
}

std::optional<std::string> sbatch(const std::vector<std::string>& args, const std::string& script,
                                  std::string* error) {
  std::string cmd = "sbatch --parsable";
  for (const auto& a : args) cmd.append(" ").append(shell_quote(a));
  cmd.append(" ").append(shell_quote(script)).append(" 2>&1");
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) {
    *error = "cannot start sbatch";
    return std::nullopt;
  }
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int status = ::pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  const std::string id = out.substr(0, out.find(';'));
  if (status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    *error = cmd + " failed" +
             (WIFEXITED(status) ? " (exit " + std::to_string(WEXITSTATUS(status)) + ")" : "") +
             (out.empty() ? "" : ": " + out);
    return std::nullopt;
  }
  return id;
}

}  // namespace curio::lab
