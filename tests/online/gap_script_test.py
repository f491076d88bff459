#!/usr/bin/env python3
"""docs/online/gap.py on committed runs (docs/online/results/): the gap is passive minus online at
the asked episode counts (anc_seed0: online .568, passive .696 at 9,666, as campaign.py's table
says), the mean row averages the runs, and a folder without curves.csv is reported, not fatal.

  python3 tests/online/gap_script_test.py REPO_ROOT
"""
import os, tempfile

from script_checks import check, finish, results, table


def rows(*args):
    return table("gap.py", *args)[1]


r = rows(os.path.join(results, "anc_seed0"), "--at", "9666")
check("anc_seed0: gap at 9,666 is .696 − .568", r[0][1] == "0.128")
r = rows(os.path.join(results, "anc_seed0"), os.path.join(results, "anc_seed3"), "--at", "9666")
check("mean row of anc seeds 0 and 3: (.128 + .159) / 2", r[2][0] == "mean of 2" and r[2][1] in ("0.143", "0.144"))
with tempfile.TemporaryDirectory() as tmp:
    r = rows(tmp, os.path.join(results, "anc_seed0"))
    check("a folder without curves.csv is reported and the others still read", r[0][1] == "no curves.csv" and r[2][0] == "mean of 1")

finish()
