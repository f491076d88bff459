// curio-archive-depth: how deep the compact archive's recipe chains get (firmware/explore/
// archive.hpp), over many seeds of a curio-lab algorithm: the lineage depth (explore
// generations from a random θ) of every archived θ, and the pool use and regeneration depth
// of this build's kThetaPoolDepth. Prints figures; asserts nothing.
//   curio-archive-depth [ALGORITHM [FIRST_SEED LAST_SEED [EPISODES]]]   (MGE-EFR 0 99 10000)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "firmware/explore/explorer.hpp"
#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/simulated_run.hpp"

namespace {

struct Totals {
  std::vector<long> lineage_histogram;  // entries by lineage depth
  int max_lineage = 0;
  int max_depth = 0;  // regeneration depth in this build
  int max_pooled = 0;
  long pooled = 0;
  long overflows = 0;
  int runs = 0;
};

void add_run(const curio::Explorer& e, Totals& t) {
  const curio::Archive& a = e.archive();
  for (int i = 0; i < a.size(); ++i) {
    const int lineage = a.lineage_depth(i);
    if (static_cast<int>(t.lineage_histogram.size()) <= lineage) {
      t.lineage_histogram.resize(static_cast<size_t>(lineage) + 1, 0);
    }
    ++t.lineage_histogram[static_cast<size_t>(lineage)];
    t.max_lineage = std::max(t.max_lineage, lineage);
    t.max_depth = std::max(t.max_depth, a.depth(i));
  }
  t.max_pooled = std::max(t.max_pooled, a.pooled());
  t.pooled += a.pooled();
  t.overflows += a.pool_overflows();
  ++t.runs;
}

int percentile(const std::vector<long>& histogram, double q) {
  long total = 0;
  for (long n : histogram) total += n;
  long seen = 0;
  for (size_t d = 0; d < histogram.size(); ++d) {
    seen += histogram[d];
    if (static_cast<double>(seen) >= q * static_cast<double>(total)) return static_cast<int>(d);
  }
  return static_cast<int>(histogram.size()) - 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace curio::lab;
  CampaignConfig c;
  c.algorithms = {argc > 1 ? argv[1] : "MGE-EFR"};
  const int first = argc > 3 ? std::atoi(argv[2]) : 0;
  const int last = argc > 3 ? std::atoi(argv[3]) : 99;
  c.episodes = argc > 4 ? std::atoi(argv[4]) : 10000;
  c.seeds.clear();
  for (int s = first; s <= last; ++s) c.seeds.push_back(s);
  if (const auto problems = validate_campaign(c); !problems.empty()) {
    for (const auto& p : problems) std::fprintf(stderr, "curio-archive-depth: %s\n", p.c_str());
    return 2;
  }
  Totals t;
  for (const RunSpec& spec : expand_runs(c)) {
    const RunResult r =
        run_exploration(spec, nullptr, [&](const curio::Explorer& e) { add_run(e, t); });
    if (!r.error.empty()) {
      std::fprintf(stderr, "curio-archive-depth: %s\n", r.error.c_str());
      return 1;
    }
  }
  long entries = 0, weighted = 0;
  for (size_t d = 0; d < t.lineage_histogram.size(); ++d) {
    entries += t.lineage_histogram[d];
    weighted += static_cast<long>(d) * t.lineage_histogram[d];
  }
  std::printf("%s, seeds %d-%d, %d episodes: %d runs, %ld archived θ\n", c.algorithms[0].c_str(),
              first, last, c.episodes, t.runs, entries);
  std::printf("lineage depth: mean %.1f, median %d, p99 %d, p99.9 %d, max %d\n",
              static_cast<double>(weighted) / static_cast<double>(entries),
              percentile(t.lineage_histogram, 0.5), percentile(t.lineage_histogram, 0.99),
              percentile(t.lineage_histogram, 0.999), t.max_lineage);
  std::printf(
      "this build (pool depth %d, pool %d θ): pooled θ per run mean %.1f, max %d; "
      "overflows %ld; deepest regeneration %d noise vectors\n",
      curio::kThetaPoolDepth, curio::kThetaPoolCapacity, static_cast<double>(t.pooled) / t.runs,
      t.max_pooled, t.overflows, t.max_depth);
  return 0;
}
