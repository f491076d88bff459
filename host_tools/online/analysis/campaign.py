#!/usr/bin/env python3
"""A campaign of curio-online seeds against the online mode's goals (ratio at 9,666 ≥ .60, a final
verdict that names exactly the ball's latents in 4 of 5 seeds): one table row per run directory
(ratio at N = 9,666 beside the same seed's passive MGE-βVAE and RPE, the final model's ball
latents, the final verdict with each module's t, effect size d = t/√n = mean/sd of the exploits'
learning progress (what t ≥ 3 needs grows as 3/√n: .19 at n = 250), relative interest and
exploits n, training time) and, with
--plot PNG, the runs' ratio curves beside the passive model's (gnuplot).

  python3 host_tools/online/analysis/campaign.py runs_online/anc_seed{0,1,2,3,4} [--plot ratio.png] [--label anchoring]

With RUN/codes_round_R.txt present for the run's last round R (codes.py's table of
the final model on the agent's own images), a last column names the latents that are a function
of the ball's position however folded (5-NN R² from the ball's position ≥ .5 and above the
distractor's, on the images where the ball moved) and whether the verdict names exactly those: the |corr| ≥ .5 rule of the
factor report sees only linear codes (evaluation only, as the other ball columns).

Training time is the sum of the run's trainings as its retrain_<r>.json files record them (a
resumed run's earlier rounds included): the time a seed needs, whatever the stops between.
"""
import argparse, csv, glob, json, os, subprocess, sys, tempfile


def load(d):
    s = json.load(open(os.path.join(d, "summary.json")))
    train_s = sum(json.load(open(f))["training"]["seconds"] for f in glob.glob(os.path.join(d, "retrain_*.json")))
    curve = list(csv.DictReader(open(os.path.join(d, "curves.csv"))))
    return s, train_s, curve


def last_round(d):
    return max(int(f.rsplit("_", 1)[1].split(".")[0]) for f in glob.glob(os.path.join(d, "retrain_*.json")))


def own_ball_latents(d):
    """The final model's ball latents on the agent's own images (evaluation only), from the last
    retrain_<r>.json (older runs' reports lack the field: then none)."""
    return sorted(json.load(open(os.path.join(d, "retrain_%d.json" % last_round(d)))).get("own_images_ball_latents", []))


def chart_ball_latents(d):
    """Latents codes.py found to be functions of the ball's position (see the docstring), or None
    when RUN/codes_round_R.txt of the last round R is absent (a table of an earlier round's model
    is not the final verdict's goal space, so it is not read)."""
    f = os.path.join(d, "codes_round_%d.txt" % last_round(d))
    if not os.path.exists(f):
        return None
    out = []
    for line in open(f):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 6 and cells[0].startswith("z") and cells[0][1:].isdigit():
            r2_ball, r2_dis = float(cells[3]), float(cells[4])
            if r2_ball >= 0.5 and r2_ball > r2_dis:
                out.append(int(cells[0][1:]))
    return sorted(out)


def verdict_cells(s):
    mods, vs = s.get("final_modules", []), s.get("final_verdicts", [])
    cells = []
    for m, v in zip(mods, vs):
        if v.get("exploits", 0) == 0:
            continue
        n = v["exploits"]
        cells.append("(%s) t %.1f d %.2f ri %.2f n %d" % (",".join("z%d" % z for z in m), v["t"],
                                                          v["t"] / n ** 0.5, v["relative_interest"], n))
    return "; ".join(cells) if cells else "-"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="curio-online run directories (finished: summary.json)")
    ap.add_argument("--plot", help="write the ratio curves to this PNG")
    ap.add_argument("--label", default="online", help="the runs' name in the figure")
    a = ap.parse_args()
    rows, curves, skipped = [], [], []
    for d in a.runs:
        if not os.path.exists(os.path.join(d, "summary.json")):
            skipped.append(d)
            continue
        s, train_s, curve = load(d)
        s["own_ball"] = own_ball_latents(d)
        s["own_match"] = bool(s["own_ball"]) and sorted(s["verdict_latents"]) == s["own_ball"]
        s["chart_ball"] = chart_ball_latents(d)
        s["chart_match"] = bool(s["chart_ball"]) and sorted(s["verdict_latents"]) == s["chart_ball"]
        rows.append((d, s, train_s))
        curves.append((s["seed"], curve))
    if not rows:
        sys.exit("campaign.py: no finished run among " + " ".join(a.runs))
    print("| seed | ratio at 9,666 | passive MGE-βVAE | RPE | ball latents (final model, held-out) | "
          "ball latents (own images) | verdict | names the ball's latents (held-out / own) | "
          "final modules with exploits: t, relative interest, exploits | training (as recorded) | "
          "ball latents by 5-NN R² (own images): verdict names them |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    zs = lambda ls: ",".join("z%d" % z for z in ls) or "none"
    for d, s, t in rows:
        chart = ("not computed" if s["chart_ball"] is None else
                 "%s: %s" % (zs(s["chart_ball"]), "yes" if s["chart_match"] else "no"))
        print("| %d | **%.3f** | %.3f | %.3f | %s | %s | %s | %s / %s | %s | %.0f min | %s |" % (
            s["seed"], s["ratio_at_9666"], s["passive_mge_beta_vae_ratio_at_9666"], s["rpe_ratio_at_9666"],
            zs(s["ball_latents_final_model"]), zs(s["own_ball"]), s["verdict_text"],
            "yes" if s["verdict_names_ball_latents"] else "no", "yes" if s["own_match"] else "no",
            verdict_cells(s), t / 60, chart))
    n = len(rows)
    mean = sum(s["ratio_at_9666"] for _, s, _ in rows) / n
    hits = sum(bool(s["verdict_names_ball_latents"]) for _, s, _ in rows)
    own_hits = sum(s["own_match"] for _, s, _ in rows)
    print("\n%d seeds: mean ratio at 9,666 %.3f (goal ≥ .60); verdict names exactly the ball's latents in %d of %d "
          "(goal 4 of 5; on the agent's own images %d of %d); training %.0f–%.0f min a seed" % (
              n, mean, hits, n, own_hits, n, min(t for *_, t in rows) / 60, max(t for *_, t in rows) / 60))
    charted = [s for _, s, _ in rows if s["chart_ball"] is not None]
    if charted:
        print("by the 5-NN reading of the final model's codes (own images): the verdict names exactly the "
              "ball's latents in %d of %d charted seeds" % (sum(s["chart_match"] for s in charted), len(charted)))
    if skipped:
        print("not finished (no summary.json): " + ", ".join(skipped))
    if a.plot:
        plot(curves, a.plot, a.label)


def plot(curves, png, label):
    with tempfile.TemporaryDirectory() as tmp:
        lines = []
        for i, (seed, curve) in enumerate(curves):
            f = os.path.join(tmp, "s%d.dat" % seed)
            with open(f, "w") as out:
                for r in curve:
                    out.write("%s %s %s\n" % (r["episodes"], r["online"], r["mge_beta_vae_passive"]))
            # explicit colours: the gray lines would otherwise take every other slot of the cycle
            lines.append("'%s' u 1:2 w l lw 2 lc %d title '%s seed %d'" % (f, i + 1, label, seed))
            lines.append("'%s' u 1:3 w l dt 2 lc rgb 'gray' notitle" % f)
        script = ("set terminal pngcairo size 900,560; set output '%s'; set key left top;"
                  "set xlabel 'episodes'; set ylabel 'exploration ratio (30x30 cells)';"
                  "set title 'curio-online ratio per seed (dashed gray: same seed, passive MGE-bVAE)';"
                  "set xrange [0:10400]; set yrange [0:0.8]; set arrow from 0,0.6 to 10400,0.6 nohead dt 3 lc rgb 'red';"
                  "plot %s\n" % (png, ", ".join(lines)))
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print("wrote " + png)


if __name__ == "__main__":
    main()
