#include "host_tools/experiment/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/gnuplot.hpp"
#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/checkpoints.hpp"
#include "host_tools/experiment/reference_results.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/experiment/statistics.hpp"

namespace curio::lab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Ten distinct line colours: gnuplot's default cycle repeats after eight, and the paper's
// figure has nine curves and the 10-module interest plots ten.
std::string line_colour(size_t i) {
  static constexpr const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                             "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                             "#bcbd22", "#17becf"};
  return std::string("rgb '") + kColours[i % std::size(kColours)] + "'";
}

std::string sigma_tag(double sigma) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", sigma);
  return buf;
}

// Results grouped by (σ, algorithm), in campaign order, failed runs left out.
std::vector<std::pair<std::pair<double, std::string>, std::vector<const RunResult*>>> group(
    const CampaignConfig& config, const std::vector<RunResult>& results) {
  std::vector<std::pair<std::pair<double, std::string>, std::vector<const RunResult*>>> groups;
  for (double sigma : config.sigmas) {
    for (const auto& algo : config.algorithms) {
      std::vector<const RunResult*> members;
      for (const auto& r : results)
        if (r.error.empty() && r.spec.explorer.sigma == static_cast<float>(sigma) &&
            r.spec.algorithm.name == algo)
          members.push_back(&r);
      if (!members.empty()) groups.push_back({{sigma, algo}, members});
    }
  }
  return groups;
}

// Mean/std/CI of the ratio at checkpoint index i across runs (all runs share checkpoints).
Summary ratio_summary(const std::vector<const RunResult*>& runs, size_t i) {
  std::vector<double> v;
  for (const auto* r : runs) v.push_back(r->ratio[i]);
  return summarize(v);
}

json summary_json(const Summary& s) {
  return {{"mean", s.mean}, {"std", s.std}, {"ci95", {s.ci95_low, s.ci95_high}}, {"n", s.n}};
}


}  // namespace

std::string run_stem(const RunSpec& s) {
  return s.algorithm.name + "_sigma" + sigma_tag(s.explorer.sigma) + "_seed" +
         std::to_string(s.explorer.seed);
}

json summarize_campaign(const CampaignConfig& config, const std::vector<RunResult>& results,
                        double wall_seconds) {
  json out;
  out["campaign"] = campaign_to_json(config);
  out["wall_seconds"] = wall_seconds;
  int failed = 0;
  for (const auto& r : results)
    if (!r.error.empty()) ++failed;
  out["failed_runs"] = failed;
  json rows = json::array();
  for (const auto& [key, runs] : group(config, results)) {
    const RunResult& first = *runs.front();
    json row;
    row["algorithm"] = key.second;
    row["sigma"] = key.first;
    row["seeds"] = runs.size();
    json cps = json::array();
    const auto spec_points = spec_checkpoints(first.checkpoints.back());
    for (size_t i = 0; i < first.checkpoints.size(); ++i) {
      const int n = first.checkpoints[i];
      const bool spec_point =
          std::find(spec_points.begin(), spec_points.end(), n) != spec_points.end();
      if (!spec_point && i + 1 != first.checkpoints.size() && n != 1000 && n != 3000 && n != 5000)
        continue;
      json cp = summary_json(ratio_summary(runs, i));
      cp["episodes"] = n;
      cps.push_back(cp);
    }
    row["checkpoints"] = cps;
    std::vector<double> grasps, secs;
    for (const auto* r : runs) {
      grasps.push_back(r->grasps.back());
      secs.push_back(r->seconds);
    }
    row["grasps"] = summary_json(summarize(grasps));
    if (!first.verdicts.empty() && first.verdicts.size() > 1) {
      json per_seed = json::array();
      std::map<std::string, int> verdict_counts;
      for (const auto* r : runs) {
        const std::string v = verdict_text(*r);
        per_seed.push_back({{"seed", r->spec.explorer.seed}, {"controllable", v}});
        ++verdict_counts[v];
      }
      json d{{"per_seed", per_seed}, {"counts", verdict_counts}};
      if (const auto truth = expected_verdict(first); !truth.empty()) {
        int matches = 0;
        for (const auto* r : runs) matches += verdict_text(*r) == truth ? 1 : 0;
        d["expected"] = truth;
        d["seeds_matching_expected"] = matches;
      }
      row["controllability"] = d;
    }
    row["seconds_per_run"] = summarize(secs).mean;
    if (const auto ref = reference_for(key.second); ref && key.first == 0.05)
      row["reference_9666"] = {{"mean", ref->mean[3]}, {"std", ref->std[3]}};
    rows.push_back(row);
  }
  out["results"] = rows;
  return out;
}

std::vector<std::string> report_files(const CampaignConfig& config) {
  std::vector<std::string> f = {"controllability.csv", "summary.json", "summary.csv", "summary.md"};
  for (const auto& spec : expand_runs(config))
    for (const char* tail : {".csv", "_interest.csv", "_scenes.csv"})
      f.push_back("runs/" + run_stem(spec) + tail);
  for (double sigma : config.sigmas) {
    const std::string ratio = "ratio_sigma" + sigma_tag(sigma);
    f.insert(f.end(), {ratio + ".png", "plots_data/" + ratio + ".gp"});
    for (const auto& name : config.algorithms) {
      const auto algo = find_algorithm(name);
      const std::string a = algo ? algo->name : name;
      const std::string stem = a + "_sigma" + sigma_tag(sigma);
      f.insert(f.end(),
               {"plots_data/ratio_" + stem + ".dat", "plots_data/reference_" + a + ".dat",
                "interest_" + stem + ".png", "plots_data/interest_" + stem + ".gp",
                "plots_data/interest_" + stem + ".dat", "ball_positions_" + stem + ".png",
                "plots_data/ball_positions_" + stem + ".gp", "plots_data/ball_" + stem + ".dat"});
    }
  }
  std::sort(f.begin(), f.end());
  f.erase(std::unique(f.begin(), f.end()), f.end());
  return f;
}

std::string format_table(const json& summary) {
  std::ostringstream o;
  o << "| algorithm | σ | seeds |";
  for (int n : kReferenceEpisodes) o << " N=" << n << " |";
  o << "\n|---|---|---|---|---|---|---|\n";
  for (const auto& row : summary["results"]) {
    o << "| " << row["algorithm"].get<std::string>() << " | " << row["sigma"].get<double>()
      << " | " << row["seeds"].get<int>() << " |";
    for (int n : kReferenceEpisodes) {
      bool found = false;
      for (const auto& cp : row["checkpoints"]) {
        if (cp["episodes"].get<int>() != n) continue;
        char buf[64];
        std::snprintf(buf, sizeof buf, " %.3f ± %.3f |", cp["mean"].get<double>(),
                      cp["std"].get<double>());
        o << buf;
        found = true;
      }
      if (!found) o << " – |";
    }
    o << "\n";
    // SPEC §4's numbers at the same checkpoints, on the line below (σ 0.05 only).
    const auto ref = reference_for(row["algorithm"].get<std::string>());
    if (ref && row["sigma"].get<double>() == 0.05) {
      o << "| ↳ SPEC §4 reference | 0.05 | " << (ref->algorithm == "RPE" ? 20 : 15) << " |";
      for (int i = 0; i < 4; ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " %.3f ± %.3f |", ref->mean[i], ref->std[i]);
        o << buf;
      }
      o << "\n";
    }
  }
  for (const auto& row : summary["results"]) {
    if (!row.contains("controllability")) continue;
    const auto& c = row["controllability"];
    o << "\n" << row["algorithm"].get<std::string>() << " (σ " << row["sigma"].get<double>()
      << ") controllable:";
    for (const auto& [verdict, n] : c["counts"].items())
      o << "  {" << verdict << "} in " << n.get<int>() << " seeds";
    if (c.contains("expected"))
      o << "  — expected {" << c["expected"].get<std::string>() << "}: "
        << c["seeds_matching_expected"].get<int>() << "/" << row["seeds"].get<int>() << " seeds";
  }
  o << "\n";
  return o.str();
}

bool write_report(const CampaignConfig& config, const std::vector<RunResult>& results,
                  const json& summary, std::vector<std::string>* warnings, std::string* error,
                  std::vector<std::string>* written) {
  const fs::path out(config.out_dir);
  // Every file is written atomically (a kill leaves the old one or the new one) and listed.
  auto write_text = [&](const fs::path& path, const std::string& text, std::string* e) {
    if (!host::write_file_atomically(path.string(), text, e)) return false;
    if (written) written->push_back(path.string());
    return true;
  };
  std::error_code ec;
  fs::create_directories(out / "runs", ec);
  fs::create_directories(out / "plots_data", ec);
  if (ec) {
    *error = "cannot create " + (out / "runs").string() + ": " + ec.message();
    return false;
  }
  // Controllable-feature verdicts, one line per run.
  {
    std::ostringstream v;
    v << "algorithm,sigma,seed,module,exploits,mean_progress,t,mean_interest,relative_interest,"
         "controllable\n";
    for (const auto& r : results) {
      for (size_t k = 0; k < r.verdicts.size(); ++k) {
        const auto& m = r.verdicts[k];
        v << r.spec.algorithm.name << ',' << r.spec.explorer.sigma << ',' << r.spec.explorer.seed
          << ',' << r.module_names[k] << ',' << m.exploits << ',' << m.mean_progress << ',' << m.t
          << ',' << m.mean_interest << ',' << m.relative_interest << ',' << (m.controllable ? 1 : 0)
          << '\n';
      }
    }
    if (!write_text(out / "controllability.csv", v.str(), error)) return false;
  }
  // Per-run CSVs.
  for (const auto& r : results) {
    if (!r.error.empty()) continue;
    std::ostringstream csv;
    csv << "episodes,exploration_ratio,grasps\n";
    for (size_t i = 0; i < r.checkpoints.size(); ++i)
      csv << r.checkpoints[i] << ',' << r.ratio[i] << ',' << r.grasps[i] << '\n';
    if (!write_text(out / "runs" / (run_stem(r.spec) + ".csv"), csv.str(), error)) return false;
    if (!r.interest.empty()) {
      std::ostringstream ic;
      ic << "episodes";
      for (const auto& name : r.module_names) ic << ",interest_" << name;
      ic << '\n';
      for (size_t i = 0; i < r.interest.size(); ++i) {
        ic << r.interest_episodes[i];
        for (float v : r.interest[i]) ic << ',' << v;
        ic << '\n';
      }
      if (!write_text(out / "runs" / (run_stem(r.spec) + "_interest.csv"), ic.str(), error))
        return false;
    }
  }
  if (!write_text(out / "summary.json", summary.dump(2) + "\n", error)) return false;
  {
    // Every checkpoint of every (algorithm, σ), beside the paper's value where it has one.
    std::ostringstream csv;
    csv << "algorithm,sigma,episodes,seeds,mean,std,ci95_low,ci95_high,paper_mean,paper_std\n";
    for (const auto& row : summary["results"]) {
      const auto ref = reference_for(row["algorithm"].get<std::string>());
      for (const auto& cp : row["checkpoints"]) {
        const int n = cp["episodes"].get<int>();
        csv << row["algorithm"].get<std::string>() << ',' << row["sigma"].get<double>() << ','
            << n << ',' << row["seeds"].get<int>() << ',' << cp["mean"].get<double>() << ','
            << cp["std"].get<double>() << ',' << cp["ci95"][0].get<double>() << ','
            << cp["ci95"][1].get<double>() << ',';
        bool found = false;
        for (int c = 0; c < 4 && ref && row["sigma"].get<double>() == 0.05; ++c)
          if (kReferenceEpisodes[c] == n) {
            csv << ref->mean[c] << ',' << ref->std[c];
            found = true;
          }
        if (!found) csv << ',';
        csv << '\n';
      }
    }
    if (!write_text(out / "summary.csv", csv.str(), error)) return false;
  }
  std::ostringstream md;
  md << "# curio-lab campaign summary\n\nExploration ratio (mean ± std over seeds), "
     << summary["campaign"]["physics"].get<std::string>() << " physics, wall time "
     << summary["wall_seconds"].get<double>() << " s.\n\n";
  if (const auto& c = summary["campaign"]; c.contains("explore"))  // absent: SPEC §2
    md << "Goal-exploration strategy: " << c["explore"].get<std::string>()
       << " (docs/beyond.md), not SPEC §2's.\n\n";
  md << format_table(summary);
  if (summary.contains("notes"))  // e.g. curio-controller: what faults did to the run
    for (const auto& n : summary["notes"]) md << "\n" << n.get<std::string>() << "\n";
  if (!write_text(out / "summary.md", md.str(), error)) return false;

  // Plots.
  // A plot that cannot be written (a full disk, a gnuplot error) fails the report like any
  // other file; only a machine without gnuplot gets a warning (its data and scripts are kept).
  std::string plot_error;
  auto plot = [&](const std::string& stem, const std::string& script) {
    if (!plot_error.empty()) return;
    std::string err;
    bool not_installed = false;
    const fs::path gp = out / "plots_data" / (stem + ".gp");
    if (!host::run_gnuplot(gp.string(), script, &err, &not_installed)) {
      if (not_installed) warnings->push_back(err);
      else plot_error = err;
    } else if (written) {
      written->insert(written->end(), {gp.string(), (out / (stem + ".png")).string()});
    }
  };
  const auto groups = group(config, results);
  for (double sigma : config.sigmas) {
    std::ostringstream gp;
    const std::string png = (out / ("ratio_sigma" + sigma_tag(sigma) + ".png")).string();
    gp << "set terminal pngcairo size 900,600 font ',11'\nset output " << host::gnuplot_quote(png)
       << "\nset title 'Exploration ratio, σ = " << sigma << " (mean and 95 % CI over seeds)'\n"
       << "set xlabel 'episodes'\nset ylabel 'exploration ratio'\nset key left top\n"
       << "set grid\nset yrange [0:*]\nset autoscale xfix\nset offsets 0, 200, 0, 0\n";
    std::vector<std::string> parts;
    size_t colour_index = 0;  // the 10-module variants are dashed
    for (const auto& [key, runs] : groups) {
      if (key.first != sigma) continue;
      const std::string colour = line_colour(colour_index++);
      const std::string dash = key.second.ends_with("-10") ? " dt 2" : "";
      const fs::path data = out / "plots_data" / ("ratio_" + key.second + "_sigma" + sigma_tag(sigma) + ".dat");
      std::ostringstream d;
      d << "# episodes mean ci_low ci_high\n";
      for (size_t i = 0; i < runs.front()->checkpoints.size(); ++i) {
        const Summary s = ratio_summary(runs, i);
        d << runs.front()->checkpoints[i] << ' ' << s.mean << ' ' << s.ci95_low << ' ' << s.ci95_high << '\n';
      }
      if (!write_text(data, d.str(), error)) return false;
      const std::string q = host::gnuplot_quote(data.string());
      parts.push_back(q + " using 1:3:4 with filledcurves fs transparent solid 0.25 noborder lc " +
                      colour + " notitle");
      parts.push_back(q + " using 1:2 with lines lw 2" + dash + " lc " + colour + " title '" +
                      key.second + "'");
      // SPEC §4's reference (mean ± std) at its four columns, in the same colour.
      if (const auto ref = reference_for(key.second); ref && sigma == 0.05) {
        const fs::path rd = out / "plots_data" / ("reference_" + key.second + ".dat");
        std::ostringstream rs;
        for (int c = 0; c < 4; ++c)
          rs << kReferenceEpisodes[c] << ' ' << ref->mean[c] << ' ' << ref->std[c] << '\n';
        if (!write_text(rd, rs.str(), error)) return false;
        parts.push_back(host::gnuplot_quote(rd.string()) +
                        " using 1:2:3 with yerrorbars pt 6 ps 1.2 lc " + colour +
                        " title '" + key.second + " (paper)'");
      }
    }
    if (parts.empty()) continue;
    gp << "plot ";
    for (size_t i = 0; i < parts.size(); ++i) gp << (i ? ", \\\n     " : "") << parts[i];
    gp << '\n';
    plot("ratio_sigma" + sigma_tag(sigma), gp.str());
  }
  for (const auto& [key, runs] : groups) {
    const RunResult& first = *runs.front();
    const std::string stem = key.second + "_sigma" + sigma_tag(key.first);
    // Interest of each module (mean over seeds).
    if (!first.interest.empty()) {
      const auto& names = first.module_names;
      const fs::path data = out / "plots_data" / ("interest_" + stem + ".dat");
      std::ostringstream d;
      for (size_t i = 0; i < first.interest.size(); ++i) {
        d << first.interest_episodes[i];
        for (size_t k = 0; k < names.size(); ++k) {
          double sum = 0;
          for (const auto* r : runs) sum += r->interest[i][k];
          d << ' ' << sum / double(runs.size());
        }
        d << '\n';
      }
      if (!write_text(data, d.str(), error)) return false;
      std::ostringstream gp;
      gp << "set terminal pngcairo size 900,500 font ',11'\nset output "
         << host::gnuplot_quote((out / ("interest_" + stem + ".png")).string())
         << "\nset title 'Interest of each module, " << key.second << ", σ = " << key.first
         << " (mean over " << runs.size() << " seeds)'\nset xlabel 'episodes'\n"
         << "set ylabel 'interest |cp|'\nset grid\nset key left top\nplot ";
      for (size_t k = 0; k < names.size(); ++k)
        gp << (k ? ", " : "") << host::gnuplot_quote(data.string()) << " using 1:" << k + 2
           << " with lines lw 2 lc " << line_colour(k) << " title '" << names[k] << "'";
      gp << '\n';
      plot("interest_" + stem, gp.str());
    }
    // Final ball positions of the first seed, on the metric's 30×30 grid.
    const fs::path data = out / "plots_data" / ("ball_" + stem + ".dat");
    std::ostringstream d;
    for (const auto& p : first.final_ball) d << p[0] << ' ' << p[1] << '\n';
    if (!write_text(data, d.str(), error)) return false;
    std::ostringstream gp;
    gp << "set terminal pngcairo size 700,700 font ',11'\nset output "
       << host::gnuplot_quote((out / ("ball_positions_" + stem + ".png")).string())
       << "\nset title 'Final ball positions, " << key.second << ", seed "
       << first.spec.explorer.seed << " (" << first.final_ball.size()
       << " episodes)'\nset size square\n"
       << "set xrange [-1:1]\nset yrange [1:-1]\nset xtics -1,0.2,1\nset ytics -1,0.2,1\n"
       << "set mxtics 3\nset mytics 3\nset grid mxtics mytics lc rgb '#dddddd'\n"
       << "set xlabel 'ball x'\nset ylabel 'ball y (image rows, +y down)'\n"
       << "set object 1 circle at 0,0 size 1 fc rgb '#888888' lw 1\n"
       << "plot " << host::gnuplot_quote(data.string())
       << " using 1:2 with points pt 7 ps 0.3 lc rgb '#c08000' notitle\n";
    plot("ball_positions_" + stem, gp.str());
  }
  if (!plot_error.empty()) {
    *error = plot_error;
    return false;
  }
  return true;
}

}  // namespace curio::lab
