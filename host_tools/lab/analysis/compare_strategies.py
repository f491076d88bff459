#!/usr/bin/env python3
"""Compares curio-lab campaigns run with different goal-exploration strategies (--explore) on
the same seeds: mean ± standard error of the exploration ratio at N = 1,000, 3,000, 5,000 and
9,666, the paired difference with the baseline campaign at 9,666 and its z (mean difference /
its standard error over seeds), and the first checkpoint at which a strategy's mean reaches the
baseline's N = 9,666 mean. Writes a markdown table, a CSV and one PNG of ratio curves (mean with
a 95 % band) per algorithm.

  compare_strategies.py --outdir docs/beyond/results \\
      spec=runs/beyond/kin_spec beyond=runs/beyond/kin_beyond ...

The first NAME=DIR is the baseline. Each DIR is a curio-lab --out folder (its runs/*.csv).
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

CHECKPOINTS = [1000, 3000, 5000, 9666]


def load(folder):
    """{(algorithm, sigma): {seed: {episodes: ratio}}} from folder/runs/<algo>_sigma<s>_seed<n>.csv."""
    runs = {}
    pattern = re.compile(r"^(.+)_sigma([0-9.]+)_seed([0-9]+)\.csv$")
    names = sorted(os.listdir(os.path.join(folder, "runs")))
    for name in names:
        m = pattern.match(name)
        if not m:
            continue
        with open(os.path.join(folder, "runs", name), newline="") as f:
            curve = {int(r["episodes"]): float(r["exploration_ratio"]) for r in csv.DictReader(f)}
        runs.setdefault((m.group(1), m.group(2)), {})[int(m.group(3))] = curve
    if not runs:
        sys.exit(f"compare_strategies: no run CSVs in {folder}/runs")
    return runs


def mean_se(values):
    n = len(values)
    m = sum(values) / n
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1)) if n > 1 else 0.0
    return m, sd / math.sqrt(n)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("campaigns", nargs="+", metavar="NAME=DIR",
                    help="strategy name and its campaign folder; the first is the baseline")
    ap.add_argument("--outdir", required=True, help="where table.md, table.csv and PNGs go")
    ap.add_argument("--prefix", default="", help="prefix of the output files (e.g. kinematic_)")
    ap.add_argument("--no-plots", action="store_true", help="write the tables only")
    args = ap.parse_args()
    pairs = []
    for c in args.campaigns:
        if "=" not in c:
            ap.error(f"'{c}' is not NAME=DIR")
        name, folder = c.split("=", 1)
        pairs.append((name, load(folder)))
    os.makedirs(args.outdir, exist_ok=True)
    base_name, base = pairs[0]
    rows = []
    curves = {}
    for key in sorted(base):
        algo, sigma = key
        b = base[key]
        b_end = mean_se([b[s][9666] for s in b])[0]
        for name, runs in pairs:
            if key not in runs:
                continue
            r = runs[key]
            seeds = sorted(r)
            row = {"algorithm": algo, "sigma": sigma, "strategy": name, "seeds": len(seeds)}
            for n in CHECKPOINTS:
                row[f"N{n}"] = mean_se([r[s][n] for s in seeds])
            common = [s for s in seeds if s in b]
            diffs = [r[s][9666] - b[s][9666] for s in common]
            d, se = mean_se(diffs) if len(diffs) > 1 else (0.0, 0.0)
            row["diff"] = d
            row["z"] = d / se if se > 0 else float("nan")
            episodes = sorted(next(iter(r.values())))
            reach = next((e for e in episodes if mean_se([r[s][e] for s in seeds])[0] >= b_end),
                         None)
            row["reaches_baseline_at"] = reach
            rows.append(row)
            curves.setdefault(algo, []).append(
                (name, [(e, *mean_se([r[s][e] for s in seeds])) for e in episodes]))

    md = [f"| algorithm | strategy | seeds | N=1000 | N=3000 | N=5000 | N=9666 | Δ at 9,666 vs "
          f"{base_name} (paired) | z | reaches {base_name}'s 9,666 mean at N |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [f"{r[f'N{n}'][0]:.3f} ± {r[f'N{n}'][1]:.3f}" for n in CHECKPOINTS]
        same = r["strategy"] == base_name
        md.append(f"| {r['algorithm']} | {r['strategy']} | {r['seeds']} | " + " | ".join(cells) +
                  (" | – | – | 9,666 |" if same else
                   f" | {r['diff']:+.3f} | {r['z']:.1f} | "
                   f"{r['reaches_baseline_at'] if r['reaches_baseline_at'] else 'not by the end'} |"))
    table = "\n".join(md) + "\n"
    with open(os.path.join(args.outdir, args.prefix + "table.md"), "w") as f:
        f.write(table)
    with open(os.path.join(args.outdir, args.prefix + "table.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["algorithm", "sigma", "strategy", "seeds"] +
                   [f"{k}_N{n}" for n in CHECKPOINTS for k in ("mean", "se")] +
                   ["diff_9666", "z_9666", "reaches_baseline_at"])
        for r in rows:
            w.writerow([r["algorithm"], r["sigma"], r["strategy"], r["seeds"]] +
                       [f"{v:.5f}" for n in CHECKPOINTS for v in r[f"N{n}"]] +
                       [f"{r['diff']:.5f}", f"{r['z']:.3f}", r["reaches_baseline_at"] or ""])
    sys.stdout.write(table)

    for algo, lines in ({} if args.no_plots else curves).items():
        safe = re.sub(r"[^A-Za-z0-9-]", "", algo.replace("β", "b"))
        dat = os.path.join(args.outdir, f"{args.prefix}curves_{safe}.dat")
        with open(dat, "w") as f:
            for name, pts in lines:
                f.write(f"# {name}\n")
                for e, m, se in pts:
                    f.write(f"{e} {m:.5f} {m - 1.96 * se:.5f} {m + 1.96 * se:.5f}\n")
                f.write("\n\n")
        png = os.path.join(args.outdir, f"{args.prefix}curves_{safe}.png")
        plots = []
        for i, (name, _) in enumerate(lines):
            plots.append(f"'{dat}' index {i} using 1:3:4 with filledcurves fs transparent solid "
                         f"0.15 lc {i + 1} notitle")
            plots.append(f"'{dat}' index {i} using 1:2 with lines lw 2 lc {i + 1} "
                         f"title '{name}' noenhanced")
        script = (f"set terminal pngcairo size 900,600\nset output '{png}'\n"
                  f"set title '{algo}: exploration ratio, mean and 95 % band' noenhanced\n"
                  "set xlabel 'episodes'\nset ylabel 'exploration ratio'\nset key left top\n"
                  "set grid\nset xrange [0:10100]\nset yrange [0:0.85]\nplot " + ", \\\n  ".join(plots) + "\n")
        p = subprocess.run(["gnuplot"], input=script, text=True, capture_output=True)
        if p.returncode != 0:
            sys.exit(f"compare_strategies: gnuplot failed for {png}: {p.stderr.strip()}")
        os.remove(dat)
        print(f"wrote {png}")


if __name__ == "__main__":
    main()
