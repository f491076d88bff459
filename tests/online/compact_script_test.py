#!/usr/bin/env python3
"""host_tools/online/analysis/compact.py on the fixture runs (tests/online/fixtures/): a run becomes
its seed's rows in <config>.csv (curves.csv's rows, seed added) and one row in runs.csv (ratio,
verdict by both readings, top module's t and d, checksum, seconds, the final code's columns); a
seed compacted again replaces its rows; a run without passive curves takes them from
--passive-from; an unfinished run is refused. Then curves.py reads the tables it wrote.

  python3 tests/online/compact_script_test.py REPO_ROOT
"""
import csv, os, shutil, tempfile

from script_checks import check, finish, fixtures, run, table

gs, r500 = os.path.join(fixtures, "gs_seed3"), os.path.join(fixtures, "r500_seed0")


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


with tempfile.TemporaryDirectory() as out:
    p = run("compact.py", "gs", gs, r500, "--outdir", out, "--commit", "abc1234")
    check("two runs compacted", p.returncode == 0)
    curves, runs = rows(os.path.join(out, "gs.csv")), rows(os.path.join(out, "runs.csv"))
    n = len(rows(os.path.join(gs, "curves.csv")))
    check("gs.csv: every curves.csv row of both seeds", len(curves) == 2 * n)
    first = {r["episodes"]: r for r in curves if r["seed"] == "3"}
    src = {r["episodes"]: r for r in rows(os.path.join(gs, "curves.csv"))}
    check("gs.csv: seed 3's curve is its curves.csv", all(
        first[e]["online"] == src[e]["online"] and first[e]["mge_beta_vae_passive"] == src[e]["mge_beta_vae_passive"]
        for e in src))
    by_seed = {r["seed"]: r for r in runs}
    s3, s0 = by_seed["3"], by_seed["0"]
    check("runs.csv: seed 3 ratio .556 beside passive .723, checksum and commit",
          (s3["ratio_at_9666"], s3["passive_ratio_at_9666"], s3["archive_checksum"], s3["commit"])
          == ("0.556", "0.723", "c3e862ba", "abc1234"))
    check("runs.csv: seed 3's verdict z2+z3, named by both readings",
          (s3["verdict"], s3["verdict_linear_rule"], s3["verdict_chart"]) == ("z2+z3", "yes", "yes"))
    check("runs.csv: seed 3's top module t 4.64 on 247 exploits, d = t/sqrt(n) .296",
          (s3["top_t"], s3["top_exploits"], s3["top_d"]) == ("4.64", "247", "0.296"))
    check("runs.csv: seed 0 (round 12) code columns from codes_round_12.txt",
          (s0["code_r2_ball_x"], s0["code_r2_ball_y"], s0["code_rest_goal_share"], s0["code_radius_corr"])
          == ("0.94", "0.93", "0.092", "0.37"))
    check("runs.csv: seed 0 trained every round itself, seed 3 resumed",
          s0["all_rounds_in_process"] == "yes" and s3["all_rounds_in_process"] == "no")

    p = run("compact.py", "gs", gs, "--outdir", out, "--commit", "def5678")
    curves, runs = rows(os.path.join(out, "gs.csv")), rows(os.path.join(out, "runs.csv"))
    check("seed 3 again: its rows replaced, not added",
          len(curves) == 2 * n and len(runs) == 2 and {r["seed"]: r["commit"] for r in runs} == {"0": "abc1234", "3": "def5678"})

    fixed = os.path.join(out, "fixed_run")
    os.makedirs(fixed)
    shutil.copy(os.path.join(gs, "summary.json"), fixed)
    with open(os.path.join(fixed, "curves.csv"), "w") as f:
        f.writelines("%s,%s\n" % (r["episodes"], r["online"]) for r in [{"episodes": "episodes", "online": "online"}]
                     + list(src.values()))
    p = run("compact.py", "fx", fixed, "--outdir", out)
    check("a run without passive curves and no --passive-from is refused", p.returncode != 0)
    p = run("compact.py", "fx", fixed, "--outdir", out, "--passive-from", os.path.join(out, "gs.csv"))
    fx = rows(os.path.join(out, "fx.csv"))
    check("--passive-from fills the passive curve of the same seed",
          p.returncode == 0 and len(fx) == n and all(r["mge_beta_vae_passive"] == first[r["episodes"]]["mge_beta_vae_passive"] for r in fx))

    p = run("compact.py", "gs", out, "--outdir", out)
    check("a folder without summary.json is refused", p.returncode != 0 and "summary.json" in p.stderr)

    _, t = table("curves.py", os.path.join(out, "gs.csv"), "--at", "9666")
    check("curves.py: mean of seeds 0 and 3 at 9,666 (.554 + .556) / 2, passive (.696 + .723) / 2",
          t[0][:2] == ["gs", "0 3"] and t[0][2] == "0.555" and t[0][3] in ("0.709", "0.710"))

finish()
