#!/usr/bin/env python3
"""When an online run falls behind: the exploration ratio's gap to passive MGE-βVAE (shipped
weights, same seed, run at the end of every curio-online run) at a few episode counts, and the
ratio each gains after the last retrain (the final goal space's own pace). Reads each run's
curves.csv (columns episodes, online, mge_beta_vae_passive), or a configuration's compact table
(docs/online/results/<config>.csv: the same columns and a seed column, one run per seed); the
ratio is read at the sample nearest each count (curves are sampled every 100 episodes).

  python3 host_tools/online/analysis/gap.py docs/online/results/anc.csv [--at 1400,3400,6400,9666] [--from 6400]
  python3 host_tools/online/analysis/gap.py runs_online/anc_seed{0,1,2,3,4}
"""
import argparse, csv, os


def counts_arg(text):
    """--at: comma-separated episode counts, at least one."""
    try:
        counts = [int(c) for c in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError("expected episode counts such as 1400,3400,9666, got %r" % text)
    return counts


def row(r):
    return int(r["episodes"]), float(r["online"]), float(r["mge_beta_vae_passive"])


def runs_of(arg):
    """[(label, curve rows)] of one argument: a run directory (its curves.csv), or a compact table
    with a seed column (one run per seed, in file order), or a single curves file; [(arg, None)]
    when there is nothing to read."""
    path = os.path.join(arg, "curves.csv") if os.path.isdir(arg) else arg
    if not os.path.isfile(path):
        return [(arg, None)]
    with open(path) as f:
        table = list(csv.DictReader(f))
    if not table:
        raise SystemExit("%s: no rows" % path)
    if "seed" not in table[0]:
        return [(arg, [row(r) for r in table])]
    seeds = {}
    for r in table:
        seeds.setdefault(r["seed"], []).append(row(r))
    name = os.path.splitext(os.path.basename(arg))[0]
    return [("%s seed %s" % (name, s), rows) for s, rows in seeds.items()]


def at(rows, n):
    """(online, passive) ratio at the sample nearest episode count n."""
    _, o, p = min(rows, key=lambda r: abs(r[0] - n))
    return o, p


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="run directories holding curves.csv (curio-online), or compact tables")
    ap.add_argument("--at", type=counts_arg, default=[1400, 3400, 6400, 9666], help="episode counts of the gap columns (comma-separated)")
    ap.add_argument("--from", dest="start", type=int, default=6400,
                    help="episode count of the last retrain: the gain columns run from here to the last --at count")
    a = ap.parse_args()
    counts = a.at
    end = counts[-1]
    print("| run | gap to passive at %s | gain %d → %d: online / passive |" % (" / ".join("{:,}".format(c) for c in counts), a.start, end))
    print("|---|---|---|")
    gaps, gains = [], []
    for label, rows in (run for d in a.runs for run in runs_of(d)):
        if rows is None:
            print("| %s | no curves.csv | |" % label)
            continue
        g = [p - o for o, p in (at(rows, c) for c in counts)]
        (o0, p0), (o1, p1) = at(rows, a.start), at(rows, end)
        gaps.append(g)
        gains.append((o1 - o0, p1 - p0))
        print("| %s | %s | %.3f / %.3f |" % (label, " / ".join("%.3f" % x for x in g), o1 - o0, p1 - p0))
    if gaps:
        k = len(gaps)
        print("| mean of %d | %s | %.3f / %.3f |" % (k, " / ".join("%.3f" % (sum(g[i] for g in gaps) / k) for i in range(len(counts))),
                                                  sum(x for x, _ in gains) / k, sum(y for _, y in gains) / k))


if __name__ == "__main__":
    main()
