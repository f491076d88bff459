#!/usr/bin/env python3
"""docs/online/gap.py on committed runs (docs/online/results/): the gap is passive minus online at
the asked episode counts (anc_seed0: online .568, passive .696 at 9,666, as campaign.py's table
says), the mean row averages the runs, and a folder without curves.csv is reported, not fatal.

  python3 tests/online/gap_script_test.py REPO_ROOT
"""
import os, subprocess, sys, tempfile

root = sys.argv[1] if len(sys.argv) > 1 else os.getcwd()
script = os.path.join(root, "docs/online/gap.py")
results = os.path.join(root, "docs/online/results")
failures = []


def rows(*args):
    out = subprocess.run([sys.executable, script, *args], capture_output=True, text=True, check=True).stdout
    return [[c.strip() for c in l.strip("|").split("|")] for l in out.splitlines()[2:]]


def check(what, cond):
    if not cond:
        failures.append(what)
    print(("ok   " if cond else "FAIL ") + what)


r = rows(os.path.join(results, "anc_seed0"), "--at", "9666")
check("anc_seed0: gap at 9,666 is .696 − .568", r[0][1] == "0.128")
r = rows(os.path.join(results, "anc_seed0"), os.path.join(results, "anc_seed3"), "--at", "9666")
check("mean row of anc seeds 0 and 3: (.128 + .159) / 2", r[2][0] == "mean of 2" and r[2][1] in ("0.143", "0.144"))
with tempfile.TemporaryDirectory() as tmp:
    r = rows(tmp, os.path.join(results, "anc_seed0"))
    check("a folder without curves.csv is reported and the others still read", r[0][1] == "no curves.csv" and r[2][0] == "mean of 1")

sys.exit(1 if failures else 0)
