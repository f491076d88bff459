#!/usr/bin/env python3
"""Ratio curves from configurations' compact tables (docs/online/results/<config>.csv, written by
compact.py): a table of the mean ratio at a few episode counts per configuration beside the mean
of the same seeds' passive MGE-βVAE, and with --plot a figure (gnuplot). One table: each seed's
curve, dashed gray its passive run. Several: each configuration's mean over its seeds, dashed
gray the passive mean (over the seeds of the first table); with --panels, one panel per table
with each seed's curve instead.

  python3 host_tools/online/analysis/curves.py docs/online/results/{prog,anc,gs,r500,anc500,a2k}.csv \\
          [--at 1400,3400,6400,9666] [--plot ratio.png [--panels]] [--title TEXT]
"""
import argparse, csv, os, subprocess, tempfile


def load(path):
    """{seed: [(episodes, online, passive)]} of one compact table, seeds in file order."""
    seeds = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            seeds.setdefault(int(r["seed"]), []).append(
                (int(r["episodes"]), float(r["online"]), float(r["mge_beta_vae_passive"])))
    if not seeds:
        raise SystemExit("curves.py: %s has no rows" % path)
    return seeds


def mean_curve(seeds, column):
    """[(episodes, mean over seeds)] at the episode counts every seed has."""
    common = set.intersection(*({e for e, *_ in rows} for rows in seeds.values()))
    by = [dict((e, r[column]) for e, *r in rows) for rows in seeds.values()]
    return [(e, sum(b[e] for b in by) / len(by)) for e in sorted(common)]


def at(curve, n):
    return min(curve, key=lambda p: abs(p[0] - n))[1]


def counts_arg(text):
    try:
        return [int(c) for c in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError("expected episode counts such as 1400,3400,9666, got %r" % text)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tables", nargs="+", help="compact tables (compact.py)")
    ap.add_argument("--at", type=counts_arg, default=[1400, 3400, 6400, 9666], help="episode counts of the table")
    ap.add_argument("--plot", help="write the figure to this PNG")
    ap.add_argument("--title", help="figure title")
    ap.add_argument("--panels", action="store_true", help="with several tables: one panel of seeds per table")
    a = ap.parse_args()
    configs = [(os.path.splitext(os.path.basename(t))[0], load(t)) for t in a.tables]
    print("| configuration | seeds | mean ratio at %s | passive, same seeds |" % " / ".join("{:,}".format(c) for c in a.at))
    print("|---|---|---|---|")
    for name, seeds in configs:
        on, pa = mean_curve(seeds, 0), mean_curve(seeds, 1)
        print("| %s | %s | %s | %s |" % (name, " ".join(str(s) for s in seeds), " / ".join("%.3f" % at(on, c) for c in a.at),
                                         " / ".join("%.3f" % at(pa, c) for c in a.at)))
    if a.plot:
        plot(configs, a.plot, a.title, a.panels)


COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"]
AXES = ("set xlabel 'episodes'; set ylabel 'exploration ratio (30x30 cells)'; set xrange [0:10400]; "
        "set yrange [0:0.8]; set grid; set key left top; set arrow 1 from 0,0.6 to 10400,0.6 nohead dt 3 lc rgb 'red';")


def seed_lines(tmp, name, seeds):
    lines = []
    for i, (seed, rows) in enumerate(seeds.items()):
        f = os.path.join(tmp, "%s_s%d.dat" % (name, seed))
        with open(f, "w") as out:
            out.writelines("%d %f %f\n" % r for r in rows)
        lines.append("'%s' u 1:2 w l lw 2 lc rgb '%s' title 'seed %d'" % (f, COLOURS[i % len(COLOURS)], seed))
        lines.append("'%s' u 1:3 w l dt 2 lc rgb 'gray' notitle" % f)
    return "plot " + ", ".join(lines) + ";"


def plot(configs, png, title, panels=False):
    with tempfile.TemporaryDirectory() as tmp:
        if len(configs) == 1:
            name, seeds = configs[0]
            title = title or "%s: ratio per seed (dashed gray: the same seed, passive MGE-bVAE)" % name
            body = "set title \"%s\" noenhanced; %s %s" % (title.replace('"', "'"), AXES, seed_lines(tmp, name, seeds))
            size = "900,560"
        elif panels:
            cols = 3
            nrows = (len(configs) + cols - 1) // cols
            title = title or "ratio per seed and configuration (dashed gray: the same seed, passive MGE-bVAE)"
            body = "set multiplot layout %d,%d title \"%s\" noenhanced; %s" % (nrows, cols, title.replace('"', "'"), AXES)
            for name, seeds in configs:
                body += " set title '%s' noenhanced; %s" % (name, seed_lines(tmp, name, seeds))
            body += " unset multiplot;"
            size = "%d,%d" % (cols * 480, nrows * 380)
        else:
            lines = []
            for i, (name, seeds) in enumerate(configs):
                f = os.path.join(tmp, "c%d.dat" % i)
                with open(f, "w") as out:
                    out.writelines("%d %f\n" % p for p in mean_curve(seeds, 0))
                lines.append("'%s' u 1:2 w l lw 2 lc rgb '%s' title '%s (%d seeds)' noenhanced"
                             % (f, COLOURS[i % len(COLOURS)], name, len(seeds)))
            f = os.path.join(tmp, "passive.dat")
            with open(f, "w") as out:
                out.writelines("%d %f\n" % p for p in mean_curve(configs[0][1], 1))
            lines.append("'%s' u 1:2 w l lw 3 dt 2 lc rgb 'gray40' title 'passive MGE-bVAE'" % f)
            title = title or "mean exploration ratio per configuration"
            body = "set title \"%s\" noenhanced; %s plot %s;" % (title.replace('"', "'"), AXES, ", ".join(lines))
            size = "900,560"
        script = "set terminal pngcairo size %s; set output '%s'; %s\n" % (size, png, body)
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print("wrote " + png)


if __name__ == "__main__":
    main()
