#!/usr/bin/env python3
"""host_tools/online/analysis/gap.py on a committed compact table (docs/online/results/anc.csv)
and on run folders (tests/online/fixtures/): the gap is passive minus online at the asked episode
counts (anc seed 0: online .568, passive .696 at 9,666), a compact table gives one row per seed,
the mean row averages the runs, and a folder without curves.csv is reported, not fatal.

  python3 tests/online/gap_script_test.py REPO_ROOT
"""
import os, tempfile

from script_checks import check, finish, fixtures, results, table


def rows(*args):
    return table("gap.py", *args)[1]


anc = os.path.join(results, "anc.csv")
r = rows(anc, "--at", "9666")
check("anc.csv: one row per seed and a mean row", [x[0] for x in r] == ["anc seed %d" % s for s in range(5)] + ["mean of 5"])
check("anc seed 0: gap at 9,666 is .696 - .568", r[0][1] == "0.128")
check("anc: mean gap at 9,666 over 5 seeds is .180", r[5][1] == "0.180")
r = rows(anc, "--at", "1400,9666", "--from", "6400")
check("anc: gap at 1,400 and 9,666 (.126 / .180), gain 6,400 -> 9,666 .100 online / .075 passive",
      r[5][1] == "0.126 / 0.180" and r[5][2] == "0.100 / 0.075")
gs, r500 = os.path.join(fixtures, "gs_seed3"), os.path.join(fixtures, "r500_seed0")
r = rows(gs, r500, "--at", "9666")
check("run folders: gs seed 3 .7233 - .5556, r500 seed 0 .6956 - .5544", r[0][1] == "0.168" and r[1][1] == "0.141")
check("run folders: mean row of 2", r[2][0] == "mean of 2" and r[2][1] in ("0.154", "0.155"))
with tempfile.TemporaryDirectory() as tmp:
    r = rows(tmp, gs)
    check("a folder without curves.csv is reported and the others still read", r[0][1] == "no curves.csv" and r[2][0] == "mean of 1")

finish()
