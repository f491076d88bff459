#!/usr/bin/env python3
"""A finished curio-online run folder (several hundred kB: reports, figures, checkpoints) reduced
to what a comparison of configurations needs, in two tables under OUTDIR:

  OUTDIR/<config>.csv   the ratio curve of every seed of the configuration:
                        seed, episodes, online, mge_beta_vae_passive, rpe (curves.csv's columns)
  OUTDIR/runs.csv       one row per run of every configuration: config, seed, commit, the ratio at
                        9,666 (online, passive MGE-βVAE and RPE of the same seed), the final
                        verdict, the module of top interest at the end (its t over the final
                        window, exploits n and effect size d = t/√n), the archive checksum, rounds,
                        whether every round was trained in the recorded process, and CPU, wall and
                        training seconds as summary.json records them (the process that finished
                        the run: a resumed run's earlier rounds are in training_seconds only),
                        and with the final model's codes table (codes.py's output saved as
                        RUN/codes_round_<R>.txt) what its ball pair holds (code_* columns)

  python3 host_tools/online/analysis/compact.py CONFIG RUN [RUN ...] [--outdir docs/online/results]
         [--commit HASH] [--passive-from CSV]

Each RUN replaces the rows of its (config, seed) in both tables, so seeds can be added one by one.
A RUN without curves.csv adds its runs.csv row only. A run without the passive baselines
(curio-online --no-baselines, or a fixed-space run) takes the passive and RPE columns of the
same seed from --passive-from (another configuration's table). verdict_chart is campaign.py's
5-NN reading of the final model's codes (yes / no, empty without codes_round_<R>.txt).
"""
import argparse, csv, glob, json, math, os, re, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import campaign  # noqa: E402  (its readers of a run folder)

CURVE_COLUMNS = ["seed", "episodes", "online", "mge_beta_vae_passive", "rpe"]
RUN_COLUMNS = ["config", "seed", "commit", "ratio_at_9666", "passive_ratio_at_9666", "rpe_ratio_at_9666",
               "verdict", "verdict_linear_rule", "verdict_chart", "top_module", "top_exploits", "top_t", "top_d",
               "archive_checksum", "rounds", "all_rounds_in_process", "cpu_seconds", "wall_seconds",
               "training_seconds", "code_pair", "code_r2_ball_x", "code_r2_ball_y", "code_rest_r2_distractor",
               "code_rest_goal_share", "code_radius_corr"]


def fmt(x, digits=3):
    return "" if x is None else ("%.*f" % (digits, x))


def run_row(config, d, commit):
    s = json.load(open(os.path.join(d, "summary.json")))
    reports = glob.glob(os.path.join(d, "retrain_*.json"))
    chart = None
    if reports:
        chart = campaign.chart_ball_latents(d)
    top = None
    for m, v in zip(s.get("final_modules", []), s.get("final_verdicts", [])):
        if v.get("exploits", 0) > 0 and (top is None or v["relative_interest"] > top[1]["relative_interest"]):
            top = (m, v)
    verdict = sorted(s.get("verdict_latents", []))
    passive = s.get("passive_mge_beta_vae_ratio_at_9666", -1)
    rpe = s.get("rpe_ratio_at_9666", -1)
    return {
        "config": config, "seed": s["seed"], "commit": commit or "",
        "ratio_at_9666": fmt(s["ratio_at_9666"]),
        "passive_ratio_at_9666": fmt(passive) if passive >= 0 else "",
        "rpe_ratio_at_9666": fmt(rpe) if rpe >= 0 else "",
        "verdict": "+".join("z%d" % z for z in verdict) or "none",
        "verdict_linear_rule": "yes" if s.get("verdict_names_ball_latents") else "no",
        "verdict_chart": "" if chart is None else ("yes" if chart and verdict == chart else "no"),
        "top_module": "+".join("z%d" % z for z in top[0]) if top else "",
        "top_exploits": top[1]["exploits"] if top else "",
        "top_t": fmt(top[1]["t"], 2) if top else "",
        "top_d": fmt(top[1]["t"] / math.sqrt(top[1]["exploits"]), 3) if top else "",
        "archive_checksum": s.get("archive_checksum", ""),
        "rounds": s.get("rounds", ""),
        "all_rounds_in_process": ("" if not reports else "no" if any(
            json.load(open(f)).get("loaded_from_checkpoint") for f in reports) else "yes"),
        "cpu_seconds": fmt(s.get("cpu_seconds_this_process"), 0),
        "wall_seconds": fmt(s.get("wall_seconds_this_process"), 0),
        "training_seconds": fmt(sum(json.load(open(f))["training"]["seconds"] for f in reports), 0) if reports else "",
        **code_columns(d),
    }


def code_columns(d):
    """The final model's code on the agent's own images, from codes.py's table of the last round
    (RUN/codes_round_<R>.txt; empty without it): the ball pair, ball (x, y) R² from it (images
    where the ball moved), the lower R² of its two latents from the distractor's position while
    the ball rests, the share of N(0, 1) goals whose nearest image has the ball at rest, and the
    correlation of the pair's code radius with the ball's distance from the arena's centre."""
    out = dict.fromkeys(["code_pair", "code_r2_ball_x", "code_r2_ball_y", "code_rest_r2_distractor",
                         "code_rest_goal_share", "code_radius_corr"], "")
    if not glob.glob(os.path.join(d, "retrain_*.json")):
        return out
    path = os.path.join(d, "codes_round_%d.txt" % campaign.last_round(d))
    if not os.path.exists(path):
        return out
    text = open(path).read()
    rest = re.search(r"R² of z(\d+), z(\d+) from the distractor's position (-?[\d.]+), (-?[\d.]+)", text)
    if rest:
        a, b = rest.group(1), rest.group(2)
        out["code_pair"] = "z%s+z%s" % (a, b)
        out["code_rest_r2_distractor"] = "%.2f" % min(float(rest.group(3)), float(rest.group(4)))
        pair = re.search(r"^\| z%s,z%s \| (-?[\d.]+) \| (-?[\d.]+) \|" % (a, b), text, re.M)
        if pair:
            out["code_r2_ball_x"], out["code_r2_ball_y"] = pair.group(1), pair.group(2)
    share = re.search(r"nearest image has the ball at rest: ([\d.]+) %", text)
    if share:
        out["code_rest_goal_share"] = "%.3f" % (float(share.group(1)) / 100)
    radius = re.search(r"centre \(moved\): corr (-?[\d.]+)", text)
    if radius:
        out["code_radius_corr"] = radius.group(1)
    return out


def read(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def write(path, columns, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, columns, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("config", help="the configuration's short name (the table's file name)")
    ap.add_argument("runs", nargs="+", help="finished curio-online run folders (summary.json)")
    ap.add_argument("--outdir", default="docs/online/results", help="where the tables are")
    ap.add_argument("--commit", help="the commit whose curio-online produced the runs (recorded in runs.csv)")
    ap.add_argument("--passive-from", help="a compact table whose passive and RPE curves fill runs that have none")
    a = ap.parse_args()
    if not a.config.replace("_", "").replace("-", "").replace(".", "").isalnum() or a.config == "runs":
        sys.exit("compact.py: CONFIG must be a plain name (letters, digits, _ - .), not 'runs'")
    passive = {}
    for r in read(a.passive_from) if a.passive_from else []:
        passive[(r["seed"], r["episodes"])] = (r["mge_beta_vae_passive"], r["rpe"])
    curves_path = os.path.join(a.outdir, a.config + ".csv")
    runs_path = os.path.join(a.outdir, "runs.csv")
    curves, runs = read(curves_path), read(runs_path)
    for d in a.runs:
        if not os.path.exists(os.path.join(d, "summary.json")):
            sys.exit("compact.py: %s has no summary.json (not a finished run)" % d)
        new = run_row(a.config, d, a.commit)
        seed = str(new["seed"])
        runs = [r for r in runs if (r["config"], r["seed"]) != (a.config, seed)] + [new]
        path = os.path.join(d, "curves.csv")
        if not os.path.exists(path):
            continue
        curves = [r for r in curves if r["seed"] != seed]
        for r in read(path):
            p = (r.get("mge_beta_vae_passive"), r.get("rpe"))
            if p[0] is None:
                if (seed, r["episodes"]) not in passive:
                    sys.exit("compact.py: %s has no passive curve and --passive-from has none for seed %s at %s"
                             % (d, seed, r["episodes"]))
                p = passive[(seed, r["episodes"])]
            curves.append({"seed": seed, "episodes": r["episodes"], "online": r["online"],
                           "mge_beta_vae_passive": p[0], "rpe": p[1]})
    os.makedirs(a.outdir, exist_ok=True)
    if curves:
        curves.sort(key=lambda r: (int(r["seed"]), int(r["episodes"])))
        write(curves_path, CURVE_COLUMNS, curves)
    runs.sort(key=lambda r: (r["config"], int(r["seed"])))
    write(runs_path, RUN_COLUMNS, runs)
    print("%s: %d seeds in %s; %d runs in %s" % (a.config, len({r["seed"] for r in curves}), curves_path,
                                                len(runs), runs_path))


if __name__ == "__main__":
    main()
